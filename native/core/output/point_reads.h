/// @file point_reads.h
/// @brief What one gathered point's indirect rays read, folded into weights on the values they read:
/// the gather at a point as a linear map, built once from the rays' hits and evaluated for each
/// lighting (internal; final_gather.h).
///
/// A point's indirect light is the mean over its rays of what each hit reads: the field blended at
/// the hit (its element's corner slots), the light around the element's corners on seams (the wedge
/// tables, times the element's reflectance), its emission taken away, or on an emitter's back side
/// its solved value. Each read is linear in those values with weights that the geometry alone
/// sets, and so are the other things the gather takes from the same rays: the halves' difference
/// and the probe field's read (gather_statistics.h), the irradiance gradients (irradiance_cache.h),
/// and the share of the light read near the point (final_gather.cpp's NearReads). Precomputed light
/// transport as a linear operator (Sloan, Kautz and Snyder 2002; per-light layers, UberBake,
/// Rodriguez et al. 2020): the rays' hits are summed into one weight per value read, far fewer than
/// rays where many rays land on one element (docs/benchmarks.md), and a re-bake or a light group's
/// layer evaluates the sum instead of reading every hit.
#pragma once

#include "output/corner_wedges.h"
#include "output/gather_statistics.h"
#include "output/irradiance_cache.h"
#include "visibility/ray_tracer.h"

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace radiosity::detail {

/// One point's reads: a term per value read with its weights, and what the rays found besides.
struct PointReads {
    /// What a term reads.
    enum class Source : uint32_t {
        FieldSlot = 0,     ///< the field at slot 4 e + k (the element's corner colours) or bubble_slot (corner_blend.h)
        BackRadiance = 1,  ///< an emitter's back side's solved radiance, per element
        Wedge = 2,         ///< a wedge table's value (CornerWedges::reflected_entry)
        Emitted = 3,       ///< an element's own emission (taken away: weight -1 a ray), of elements that may emit
    };
    /// A value read and its weights, summed over the rays in double precision and kept in single:
    /// 12 bytes a term, where a kept hit takes 16. The index has 30 bits: a scene's elements (at
    /// most ElementLimits::max_elements) have 5 slots each (4 corners and a bubble), far fewer.
    struct Term {
        uint32_t read = 0;        ///< the source in the top two bits, the slot, element or table value below
        float sum = 0.0f;         ///< weight in the rays' sum
        float difference = 0.0f;  ///< weight in the halves' difference (half_sign)

        static constexpr uint32_t kIndexBits = 30;
        Source source() const { return Source(read >> kIndexBits); }
        std::size_t index() const { return read & ((1U << kIndexBits) - 1U); }
    };
    /// A term's weights in the gradients (gradient_weights), in single precision: the gradients only
    /// carry a record's light to the points read from it.
    struct GradientTerm {
        glm::vec2 rotation{0.0f}, translation{0.0f};  ///< in the rays' tangent frame (GradientWeights)
    };
    std::vector<Term> terms;
    std::vector<GradientTerm> gradients;  ///< per term (empty: folded without the gradients)
    std::vector<float> back_distances;    ///< how far the rays that met a back face went
    int rays = 0, near_hits = 0;          ///< rays cast; those that met a surface near the point (RayGrid)
    /// The field slots the rays met near the point, each once with its summed weight over the rays
    /// divided by their count (final_gather.cpp's NearReads): the rays' sum less these is the rest.
    std::vector<std::pair<int32_t, double>> near_slots;

    std::size_t bytes() const;
};

/// One ray of a point's gather: what it hit (patch < 0: nothing) and whether it met its front.
struct RayHit {
    hr::Visibility::Hit hit;
    bool front = false;
};

/// How the rays were cast and what counts as near: `grid` x `grid` stratified rays; a hit closer
/// than `near` times the square root of its element's area is near the point.
struct RayGrid {
    int grid = 1;
    float near = 0.0f;
    bool gradients = false;  ///< fold the gradients' weights too
    bool bubbles = false;    ///< read the elements' bubbles too (the field carries them: corner_blend.h)
};

/// `hits` (ray i in the order cast) folded into weights; `emitted`: each element's own emission
/// (which elements may emit); `wedges` may be null (no tables read).
PointReads fold_reads(const Elements& elements, const std::vector<Rgb>& emitted, const CornerWedges* wedges,
                      const RayGrid& grid, const std::vector<RayHit>& hits);

/// The values a point's reads are evaluated on.
struct ReadValues {
    const Elements& elements;
    const std::vector<Rgb>& field;     ///< 4 an element, then a bubble an element if folded with them
    const std::vector<Rgb>& radiance;  ///< solved, per element
    const std::vector<Rgb>& emitted;   ///< own emission, per element
    const CornerWedges* wedges;        ///< null: none
    const std::vector<Rgb>* probe;     ///< the probe field, 4 an element (null: not read)
};

/// The sums a point's reads give (each over its rays, not yet divided by their count); `rest`: the
/// sum less what the rays read of the field near the point.
struct ReadSums {
    Rgb sum{0.0}, rest{0.0}, difference{0.0}, probe{0.0};
    PlaneGradients gradients;  ///< of the mean (the weights hold the division), in the rays' tangent frame
};

/// What `reads` give over `values`.
ReadSums evaluate(const PointReads& reads, const ReadValues& values);

}  // namespace radiosity::detail
