/// @file final_gather.cpp
/// @brief Direct light and one bounce of gathered indirect light at the output corners (final_gather.h).
#include "output/final_gather.h"

#include "common/parallel_rows.h"
#include "common/stratified.h"
#include "geometry/weld.h"
#include "output/coincident_faces.h"
#include "output/corner_approach.h"
#include "output/corner_blend.h"
#include "output/corner_wedges.h"
#include "output/emitter_groups.h"
#include "output/flat_places.h"
#include "output/gather_hits.h"
#include "output/irradiance_cache.h"
#include "output/kept_direct_light.h"
#include "output/lamp_bubbles.h"
#include "output/point_reads.h"
#include "transport/lamp_points.h"
#include "transport/near_field.h"
#include "transport/world_light.h"
#include "visibility/ray_tracer.h"
#include "visibility/shadow_ray.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>

namespace radiosity::detail {
namespace {

/// What a point's rays read of the corner field near it (closer than kNear times the size of the
/// element hit): the light there is the neighbouring points' own gathered light, so the point's
/// light is linear in it, light = direct + max(indirect + sum of weight x field[slot], 0).
struct NearReads {
    Rgb direct{0.0}, indirect{0.0};                 ///< direct light; the other rays' indirect light
    std::vector<std::pair<int32_t, double>> slots;  ///< (slot 4 e + k of the field, weight), each slot once
};

/// What a gathered point gives besides its light, each where its pointer is not null.
struct PointOutputs {
    NearReads* reads = nullptr;             ///< what its rays read near it (the last pass)
    PointStatistics* statistics = nullptr;  ///< its sampling statistics (gather_statistics.h)
    LightGradients* gradients = nullptr;    ///< its indirect light's gradients (irradiance_cache.h)
    uint8_t* moved = nullptr;               ///< whether its first point was buried and another taken
};

/// Per element vertex, the direct light the field found there (gather_field), where it is known.
struct KnownDirectLight {
    std::vector<Rgb> light;
    std::vector<uint8_t> known;
    bool at(int32_t vertex) const { return !known.empty() && known[std::size_t(vertex)] != 0; }
};

/// What a point's probe rays found (Gatherer::probe): where it is gathered, the harmonic mean and
/// the least of their hit distances, and whether any met a back face (it may be buried).
struct Probe {
    Vec3 position{0.0f};
    double harmonic_distance = 0.0, nearest = 0.0;
    bool back_face = false;
};

/// Each element's corners as the gather's rays see them, `backs` false: every element that blocks
/// light but the back sides, which coincide with their fronts (both sides of a patch occlude);
/// `backs` true: only the back sides, where a ray that met a front from behind finds what it sees.
std::vector<std::array<int32_t, 4>> ray_corners(const Elements& elements, bool backs) {
    std::vector<std::array<int32_t, 4>> corners = blocking_corners(elements);
    for (std::size_t e = 0; e < corners.size(); ++e)
        if (elements.is_back(e) != backs) corners[e] = {corners[e][0], corners[e][0], corners[e][0], -1};
    return corners;
}

/// The direct light at a point, in parts (Gatherer::direct_at): what a nearby point's light is
/// compared with.
struct DirectParts {
    EmitterGroups emitters;
    std::vector<double> share;  ///< each group's visible share
    Rgb lamps{0.0};
};

/// What every Gatherer of one final_gather shares: the elements and their light, the sources and
/// their signatures (kept_direct_light.h), the ray tracers and what earlier gathers kept.
struct GatherScene {
    const Elements& elements;
    const std::vector<Rgb>& emitted;   ///< each element's own emission
    const std::vector<Rgb>& radiance;  ///< the solved radiance (read flat on emitters' back sides)
    const Lights& lights;
    const WorldSampler& world;
    const std::vector<Emitter>& emitters;
    const std::vector<EmitterRun>& runs;
    const hr::Visibility& visibility;
    const hr::Visibility* back_sides;  ///< the back sides alone (null: there are none)
    const CoincidentFaces& coincident;
    float scene_size;
    SourceSignatures signatures;
    GatherKept kept;
};

/// How a Gatherer reads its indirect rays: hit by hit (the field's and the wedge tables' few rays,
/// which land on nearly as many values as there are rays), or folded into the values they read
/// (the output's many rays, which land on far fewer values: docs/benchmarks.md), which a re-bake or
/// a light group's layer then reads in a fraction of the time.
enum class RayKeeping { HitByHit, Folded };

/// The gather at one point: its element, where it starts and what it found.
class Gatherer {
public:
    Gatherer(const GatherScene& scene, const std::vector<Rgb>& corner_field, const FinalGatherSettings& settings,
             const CornerWedges* wedges = nullptr, RayKeeping keeping = RayKeeping::HitByHit)
        : scene_(scene),
          elements_(scene.elements),
          corner_field_(corner_field),
          wedges_(wedges),
          keeping_(keeping),
          grid_(std::max(1, int(std::ceil(std::sqrt(double(std::max(1, settings.rays)) - 1e-9))))),
          shadow_rays_(std::max(1, settings.shadow_rays)) {}

    /// The radiance at element vertex `vertex` of element `e` (of a polygon centred at
    /// `polygon_centre`); false when the point is buried. `place` seeds the rays: vertices at one
    /// place get the same directions, so coplanar faces around a vertex differ only where the
    /// light does. `light`: the light arriving there, direct + indirect (irradiance / pi).
    /// `direct`: the point's direct light, computed when `direct_known` is false or the first point
    /// is buried (given: the direct light at the first point, from the field or an earlier pass).
    bool radiance_at(int32_t vertex, std::size_t e, const Vec3& polygon_centre, const Vec3& approach, uint32_t place,
                     Rgb& out, Rgb& light, float& near_share, Rgb& direct_light, bool direct_known,
                     const PointOutputs& outputs = {}) const {
        const Vec3 corner = elements_.vertices[vertex];
        const Vec3 towards = elements_.centre[e] - corner;
        const float to_centre = glm::length(towards);
        const Vec3 n = elements_.normal[e];
        const uint32_t seed = mix_seed(place, 0x5EEDU);
        // A hair into the element (along the corner's approach, corner_approach.h, if it has one);
        // if that is buried, further in, then further into the polygon (its element may lie wholly
        // under what buries it: a floor cut along a wall's footprint).
        std::array<Vec3, 6> candidates;
        int count = 0;
        if (to_centre > 0.0f) {
            candidates[count++] = first_point(vertex, e, approach);
            candidates[count++] = corner + 0.1f * towards;
            candidates[count++] = corner + 0.5f * towards;
            const Vec3 inwards = polygon_centre - corner;
            const float to_polygon_centre = glm::length(inwards);
            for (const float distance : {1.0f, 2.0f, 4.0f})
                if (distance * to_centre < 0.9f * to_polygon_centre)
                    candidates[count++] = corner + (distance * to_centre / to_polygon_centre) * inwards;
        } else {
            candidates[count++] = corner;
        }
        for (int i = 0; i < count; ++i) {
            const Vec3 x = candidates[i];
            if (scene_.coincident.covered(x, e)) continue;  // buried under another face (coincident_faces.h)
            Rgb indirect(0.0);
            if (!gather_indirect(x, n, seed, to_centre, indirect, near_share, outputs)) continue;  // buried
            // The light arriving is gathered on black surfaces too: it is the light-only output.
            if (!direct_known || i > 0) direct_light = direct(x, lifted(x, n), n, seed);
            if (outputs.reads != nullptr) outputs.reads->direct = direct_light;
            light = direct_light + indirect;
            out = scene_.emitted[e] + elements_.reflectance[e] * light;
            if (outputs.moved != nullptr) *outputs.moved = i > 0;
            return true;
        }
        return false;
    }

    /// The radiance at element vertex `vertex` of element `e` gathered at the point where Cycles
    /// bakes it even where that is buried (inside other geometry): rays that meet back faces bring
    /// nothing and the shadow rays find the lamps hidden, as Cycles' rays find the inside of a
    /// closed solid unlit; on another face facing the same way, only its own emission. Whether the
    /// point is buried there, as radiance_at judges it.
    bool buried_at_corner(int32_t vertex, std::size_t e, const Vec3& approach, uint32_t place, Rgb& out,
                          Rgb& light) const {
        const Vec3 x = first_point(vertex, e, approach);
        const Vec3 n = elements_.normal[e];
        if (scene_.coincident.covered(x, e)) {
            light = Rgb(0.0);
            out = scene_.emitted[e];
            return true;
        }
        const uint32_t seed = mix_seed(place, 0x5EEDU);
        Rgb indirect(0.0);
        float near_share = 0.0f;
        if (gather_indirect(x, n, seed, glm::length(elements_.centre[e] - x), indirect, near_share, {}, true))
            return false;
        light = direct(x, lifted(x, n), n, seed) + indirect;
        out = scene_.emitted[e] + elements_.reflectance[e] * light;
        return true;
    }

    /// Whether element vertex `vertex` of element `e` is gathered where another polygon's face lies
    /// on its own (coincident_faces.h).
    bool covered(int32_t vertex, std::size_t e, const Vec3& approach) const {
        return scene_.coincident.covered(first_point(vertex, e, approach), e);
    }

    /// The direct light (irradiance / pi) where element vertex `vertex` of element `e` is gathered,
    /// as radiance_at finds it there.
    Rgb direct_light(int32_t vertex, std::size_t e, const Vec3& approach, uint32_t place) const {
        const Vec3 x = first_point(vertex, e, approach), n = elements_.normal[e];
        return direct(x, lifted(x, n), n, mix_seed(place, 0x5EEDU));
    }

    /// `rays` stratified cosine-weighted rays from where element vertex `vertex` of element `e` is
    /// gathered: the harmonic mean of the distances to what they meet (rays that leave the scene do
    /// not count: near an opening the light changes as fast as the distance to its edges says;
    /// `far` when all leave), the nearest, and whether any met a back face.
    Probe probe(int32_t vertex, std::size_t e, const Vec3& approach, uint32_t place, int rays, float far) const {
        Probe out;
        out.position = first_point(vertex, e, approach);
        const glm::dvec3 n(elements_.normal[e]);
        glm::dvec3 t, b;
        tangent_frame(n, t, b);
        const Vec3& origin = out.position;
        const int grid = std::max(1, int(std::lround(std::sqrt(double(rays)))));
        uint32_t seed = mix_seed(place, 0x960BEU);
        RecordedRays recorded(scene_.kept.hits, origin, elements_.normal[e], seed, grid, GatherHits::Kind::Probe);
        double inverse = 0.0;
        int hits = 0;
        out.nearest = far;
        for (int i = 0; i < grid * grid; ++i) {
            bool meets_back = false;
            const hr::Visibility::Hit hit = recorded.hit(i, meets_back, [&] {
                const double u = (double(i % grid) + next_jitter(seed)) / grid;
                const double v = (double(i / grid) + next_jitter(seed)) / grid;
                const Vec3 direction(cosine_direction(n, t, b, u, v));
                // The fronts alone, whether or not they emit: which points gather may not depend on the light.
                const hr::Visibility::Hit traced = scene_.visibility.first_hit_from_surface(origin, Vec3(n), direction);
                return std::make_pair(traced,
                                      traced.patch >= 0 && glm::dot(direction, elements_.normal[traced.patch]) >= 0.0f);
            });
            const double distance = hit.patch < 0 ? double(far) : std::min(double(far), double(hit.distance));
            if (hit.patch >= 0) {
                inverse += 1.0 / std::max(distance, 1e-12);
                ++hits;
            }
            out.nearest = std::min(out.nearest, distance);
            out.back_face |= meets_back;
        }
        out.harmonic_distance = hits > 0 ? double(hits) / inverse : double(far);
        recorded.finish();
        return out;
    }

    /// The emitters' and lamps' direct light at `x`, a hair inside element `e`, in parts, seeded as
    /// a point at `place` is.
    DirectParts direct_at(const Vec3& x, std::size_t e, uint32_t place) const {
        const Vec3 n = elements_.normal[e];
        const uint32_t seed = mix_seed(place, 0x5EEDU);
        KeptDirectLight::Point kept(scene_.kept.direct, x, n, seed);
        DirectParts parts = direct_parts(x, lifted(x, n), n, seed, kept);
        kept.finish();
        return parts;
    }

    /// How much more direct light arrives at `x`, a hair inside element `e` next to the point of
    /// `from`, than there: the emitters' unoccluded light as at that point (so near each other it
    /// differs only by what hides them), times the change in their visible share along the same
    /// shadow rays, and the lamps'. The world's light is taken to be the same.
    Rgb direct_change(const DirectParts& from, const Vec3& x, std::size_t e, uint32_t place) const {
        const Vec3 n = elements_.normal[e];
        const uint32_t seed = mix_seed(place, 0x5EEDU);
        KeptDirectLight::Point kept(scene_.kept.direct, x, n, seed);
        Rgb change(0.0);
        for (std::size_t g = 0; g < from.emitters.groups.size(); ++g) {
            const EmitterGroup& group = from.emitters.groups[g];
            if (!(max_channel(group.light) > 0.0)) continue;
            const double share = kept_share(from.emitters, group, lifted(x, n), n, seed, kept);
            change += group.light * (share - from.share[g]);
        }
        if (!scene_.lights.empty()) change += kept_lamps(x, n, kept) / M_PI - from.lamps;
        kept.finish();
        return change;
    }

    /// The indirect light at `x`, a hair inside element `e`, along the rays of a point at `place`;
    /// false where it is buried.
    bool indirect_near(const Vec3& x, std::size_t e, uint32_t place, Rgb& out) const {
        const Vec3 n = elements_.normal[e];
        float near_share = 0.0f;
        return gather_indirect(x, n, mix_seed(place, 0x5EEDU), glm::length(elements_.centre[e] - x), out, near_share,
                               {});
    }

    /// Where the gather at element vertex `vertex` of element `e` starts, unless that is buried.
    Vec3 first_point(int32_t vertex, std::size_t e, const Vec3& approach) const {
        const Vec3 corner = elements_.vertices[vertex];
        const Vec3 towards = elements_.centre[e] - corner;
        const float to_centre = glm::length(towards);
        if (!(to_centre > 0.0f)) return corner;
        if (glm::dot(approach, approach) > 0.0f) {
            // Where Cycles bakes an input corner, along the approach.
            return corner + std::min(to_centre, bake_offset(corner, scene_.scene_size)) * approach;
        }
        const float hair = std::min(1e-3f * to_centre, 1e-4f * scene_.scene_size);
        return corner + (hair / to_centre) * towards;
    }

private:
    /// Mean of (radiance - own emission) over the first hits of cosine-weighted rays; false when
    /// more than half of them hit a back face nearer than `near` (buried: then `out` is left as it
    /// was unless `even_buried`). The radiance where a ray hit is radiance_near plus the light
    /// around its corners on seams (wedge_light); both are linear in the values they read.
    /// The rays leave `origin`, the point itself, skipping its own face (as Cycles' rays do).
    /// `near_share`: the share of rays that met a surface near the point (closer than kNear times
    /// the size of the element hit). With `outputs.reads` (the output's gatherers alone), what those
    /// rays read of the field goes there as weights, the rest as its indirect; with
    /// `outputs.statistics` and `outputs.gradients`, the rays' sampling statistics and the indirect
    /// light's gradients. The output's gatherers read their rays folded (point_reads.h), the others
    /// hit by hit.
    bool gather_indirect(const Vec3& origin, const Vec3& normal, uint32_t seed, float near, Rgb& out, float& near_share,
                         const PointOutputs& outputs, bool even_buried = false) const {
        if (keeping_ == RayKeeping::Folded)
            return gather_folded(origin, normal, seed, near, out, near_share, outputs, even_buried);
        return gather_hit_by_hit(origin, normal, seed, near, out, near_share, outputs, even_buried);
    }

    /// gather_indirect from the rays' folded reads, kept by an earlier gather or traced and folded.
    bool gather_folded(const Vec3& origin, const Vec3& normal, uint32_t seed, float near, Rgb& out, float& near_share,
                       const PointOutputs& outputs, bool even_buried) const {
        PointReads own;
        const PointReads& reads = point_reads(origin, normal, seed, outputs.gradients != nullptr, own);
        const int rays = reads.rays;
        const auto back_near = std::count_if(reads.back_distances.begin(), reads.back_distances.end(),
                                             [&](float distance) { return distance < near; });
        const bool buried = 2 * back_near > rays;
        if (buried && !even_buried) return false;
        PointStatistics* statistics = outputs.statistics;
        const ReadSums sums = evaluate(reads, {elements_, corner_field_, scene_.radiance, scene_.emitted, wedges_,
                                               statistics != nullptr ? statistics->probe : nullptr});
        out = glm::max(sums.sum / double(rays), Rgb(0.0));
        near_share = float(reads.near_hits) / float(rays);
        if (statistics != nullptr) spread_statistics(out, sums.difference, sums.probe, rays, *statistics);
        if (outputs.gradients != nullptr) {
            glm::dvec3 t, b;
            tangent_frame(glm::dvec3(normal), t, b);
            *outputs.gradients = sums.gradients.in_space(t, b);
        }
        if (outputs.reads != nullptr) {
            outputs.reads->slots = reads.near_slots;
            outputs.reads->indirect = sums.rest / double(rays);
        }
        return !buried;
    }

    /// The folded reads of the rays from `origin` (with the gradients' weights if `gradients`): kept
    /// by an earlier gather, else traced and folded into `own`, and kept if the budget allows.
    const PointReads& point_reads(const Vec3& origin, const Vec3& normal, uint32_t seed, bool gradients,
                                  PointReads& own) const {
        const bool with_wedges = wedges_ != nullptr && !wedges_->empty();
        const bool bubbles = has_bubbles(corner_field_, elements_);
        const uint32_t read = (with_wedges ? GatherHits::kWithWedges : 0U) |
                              (gradients ? GatherHits::kWithGradients : 0U) | (bubbles ? GatherHits::kWithBubbles : 0U);
        const GatherHits::Key key = GatherHits::key(origin, normal, seed, grid_, GatherHits::Kind::Indirect, read);
        GatherHits* hits = scene_.kept.hits;
        if (hits != nullptr)
            if (const PointReads* kept = hits->find_reads(key)) return *kept;
        own = fold_reads(elements_, scene_.emitted, with_wedges ? wedges_ : nullptr, {grid_, kNear, gradients, bubbles},
                         trace_rays(origin, normal, seed));
        if (hits != nullptr)
            if (const PointReads* kept = hits->record_reads(key, own)) return *kept;
        return own;
    }

    /// The stratified cosine-weighted rays from `origin`, in order, and whether each met a front.
    std::vector<RayHit> trace_rays(const Vec3& origin, const Vec3& normal, uint32_t seed) const {
        glm::dvec3 t, b;
        const glm::dvec3 n(normal);
        tangent_frame(n, t, b);
        std::vector<RayHit> hits(std::size_t(grid_) * std::size_t(grid_));
        for (int i = 0; i < grid_ * grid_; ++i) hits[std::size_t(i)] = trace_ray(origin, n, t, b, i, seed);
        return hits;
    }

    /// Ray `i` of the stratified cosine-weighted rays from `origin` (its jitter drawn from `seed`):
    /// what it hit and whether it met a front.
    RayHit trace_ray(const Vec3& origin, const glm::dvec3& n, const glm::dvec3& t, const glm::dvec3& b, int i,
                     uint32_t& seed) const {
        const double u = (double(i % grid_) + next_jitter(seed)) / grid_;
        const double v = (double(i / grid_) + next_jitter(seed)) / grid_;
        const Vec3 direction(cosine_direction(n, t, b, u, v));
        const hr::Visibility::Hit traced =
            facing(scene_.visibility.first_hit_from_surface(origin, Vec3(n), direction), origin, direction);
        return {traced, traced.patch >= 0 && glm::dot(direction, elements_.normal[traced.patch]) < 0.0f};
    }

    /// gather_indirect reading each ray's hit, recorded by an earlier gather or traced (without
    /// `outputs.reads` and `outputs.gradients`: only the output's gatherers ask for those).
    bool gather_hit_by_hit(const Vec3& origin, const Vec3& normal, uint32_t seed, float near, Rgb& out,
                           float& near_share, const PointOutputs& outputs, bool even_buried) const {
        glm::dvec3 t, b;
        const glm::dvec3 n(normal);
        tangent_frame(n, t, b);
        Rgb sum(0.0);
        int back_near = 0, near_hits = 0;
        RaySpread spread(elements_, outputs.statistics, grid_);
        RecordedRays recorded(scene_.kept.hits, origin, normal, seed, grid_, GatherHits::Kind::Indirect);
        const int rays = grid_ * grid_;
        for (int i = 0; i < rays; ++i) {
            bool meets_front = false;
            const hr::Visibility::Hit hit = recorded.hit(i, meets_front, [&] {
                const RayHit traced = trace_ray(origin, n, t, b, i, seed);
                return std::make_pair(traced.hit, traced.front);
            });
            if (hit.patch < 0) continue;
            if (meets_front) {
                const Rgb seen = radiance_near(hit) + wedge_light(hit) - scene_.emitted[hit.patch];
                sum += seen;
                spread.add(i, seen, hit);
                near_hits += hit.distance < kNear * std::sqrt(elements_.area[hit.patch]);
            } else {
                back_near += hit.distance < near;
            }
        }
        recorded.finish();
        const bool buried = 2 * back_near > rays;
        if (buried && !even_buried) return false;
        out = glm::max(sum / double(rays), Rgb(0.0));
        near_share = float(near_hits) / float(rays);
        spread.finish(out, rays);
        return !buried;
    }

    /// `hit`, or where it is on an emitting polygon's element seen from behind, the back side
    /// there, which faces the ray (its own element and parameters: a hierarchy refines the two
    /// sides apart).
    hr::Visibility::Hit facing(hr::Visibility::Hit hit, const Vec3& origin, const Vec3& direction) const {
        if (hit.patch < 0 || glm::dot(direction, elements_.normal[hit.patch]) < 0.0f) return hit;
        if (scene_.back_sides == nullptr || !elements_.has_twin(std::size_t(hit.patch))) return hit;
        const float tolerance = 1e-5f * scene_.scene_size + 1e-4f * hit.distance;
        const hr::Visibility::Hit back =
            scene_.back_sides->first_hit(origin, direction, std::max(0.0f, hit.distance - tolerance));
        return back.patch >= 0 && back.distance <= hit.distance + tolerance ? back : hit;
    }

    /// Emitting elements at x (exact unoccluded factors times their visible share), lamps and the
    /// world (EmitterGroups), each source's part read where the gathers before kept it.
    Rgb direct(const Vec3& x, const Vec3& origin, const Vec3& normal, uint32_t seed) const {
        KeptDirectLight::Point kept(scene_.kept.direct, x, normal, seed);
        const DirectParts parts = direct_parts(x, origin, normal, seed, kept);
        Rgb light(0.0);
        for (std::size_t g = 0; g < parts.share.size(); ++g) light += parts.emitters.groups[g].light * parts.share[g];
        light += parts.lamps;
        if (!scene_.world.empty())
            light += kept.light(scene_.signatures.world, [&] {
                return scene_.world.irradiance(scene_.visibility, origin, normal, mix_seed(seed, 0x3011DU));
            }) / M_PI;
        kept.finish();
        return light;
    }

    /// The emitters' light at x (each group's exact unoccluded light and visible share from `origin`)
    /// and the lamps'. The factors are taken at `origin` too: at x itself, which lies in its own
    /// element's plane, round-off may put x in front of that element's back side (an emitter that
    /// emits from both sides), whose factor from a point in its plane is then the whole hemisphere.
    DirectParts direct_parts(const Vec3& x, const Vec3& origin, const Vec3& normal, uint32_t seed,
                             KeptDirectLight::Point& kept) const {
        DirectParts parts{
            emitter_groups(scene_.emitters, scene_.runs, glm::dvec3(origin), glm::dvec3(normal)), {}, Rgb(0.0)};
        for (const EmitterGroup& group : parts.emitters.groups)
            parts.share.push_back(kept_share(parts.emitters, group, origin, normal, seed, kept));
        if (!scene_.lights.empty()) parts.lamps = kept_lamps(x, normal, kept) / M_PI;  // its rays leave a gap
        return parts;
    }

    /// The lamps' irradiance at x, each traced lamp's read from `kept` under its signature if there.
    Rgb kept_lamps(const Vec3& x, const Vec3& normal, KeptDirectLight::Point& kept) const {
        return lamp_irradiance_through(scene_.lights, scene_.visibility, x, normal,
                                       [&](std::size_t l, bool fully, const auto& trace) {
                                           return kept.light(scene_.signatures.lamps[l][fully], trace);
                                       });
    }

    /// visible_share, read from `kept` under the group's signature if there.
    double kept_share(const EmitterGroups& groups, const EmitterGroup& group, const Vec3& origin, const Vec3& normal,
                      uint32_t seed, KeptDirectLight::Point& kept) const {
        if (!(max_channel(group.light) > 0.0)) return 0.0;
        return kept
            .light(group_signature(groups, group),
                   [&] { return Rgb(visible_share(groups, group, origin, normal, seed)); })
            .r;
    }

    /// How many shadow rays `group` gets of the point's (visible_share).
    double group_rays(const EmitterGroups& groups, const EmitterGroup& group) const {
        return std::max(1.0, std::round(shadow_rays_ * max_channel(group.light) / groups.total));
    }

    /// What visible_share reads besides the point and the geometry: the group's elements (those
    /// facing the point), their radiance relative to the group's brightest (so an emission's
    /// strength changed alone keeps the share) and its rays.
    uint64_t group_signature(const EmitterGroups& groups, const EmitterGroup& group) const {
        Signature signature;
        signature.word(0x6A0U).number(group_rays(groups, group)).number(group.area);
        signature.word(uint32_t(group.first)).word(uint32_t(group.last));
        if (group.whole) return signature.word(0xA11U).value();  // every element, all alike
        const double brightest = brightest_radiance(groups, group);
        for (std::size_t i = group.first; i < group.last; ++i) {
            signature.word(groups.faces[i]);
            if (groups.faces[i]) signature.number(max_channel(scene_.emitters[i].radiance) / brightest);
        }
        return signature.value();
    }

    /// The largest channel of the brightest of `group`'s elements that face the point.
    double brightest_radiance(const EmitterGroups& groups, const EmitterGroup& group) const {
        if (group.whole) return max_channel(scene_.emitters[group.first].radiance);
        double brightest = 0.0;
        for (std::size_t i = group.first; i < group.last; ++i)
            if (groups.faces[i]) brightest = std::max(brightest, max_channel(scene_.emitters[i].radiance));
        return brightest;
    }

    /// The share of `group` that shadow rays from `origin` find unhidden. The group gets its share of
    /// `shadow_rays` by its unoccluded light (at least one), spread over its elements by area
    /// (systematic sampling) and stratified within each; the share is weighted by the kernel
    /// cos cos / r^2 and the elements' radiance relative to the brightest's (a share, it does not
    /// change with the group's strength). So a wall split into a thousand emitting elements costs
    /// its share of the rays, not a thousand.
    double visible_share(const EmitterGroups& groups, const EmitterGroup& group, const Vec3& origin, const Vec3& normal,
                         uint32_t seed) const {
        const double weight = max_channel(group.light);
        if (!(weight > 0.0)) return 0.0;
        const double rays = group_rays(groups, group);
        uint32_t pick_seed = mix_seed(seed, uint32_t(scene_.emitters[group.first].element) ^ 0x9A0BU);
        double next_pick = next_jitter(pick_seed) * group.area / rays;
        double visible = 0.0, seen = 0.0;
        int clear = 0, cast = 0;
        const double brightest = brightest_radiance(groups, group);
        std::array<Vec3, 256> points;
        auto cast_at = [&](std::size_t i, int picks) {  // `picks` of the rays at emitter i, stratified
            const Emitter& source = scene_.emitters[i];
            const int grid = std::clamp(int(std::lround(std::sqrt(double(picks)))), 1, 16);
            std::array<Vec3, 4> c;
            for (int k = 0; k < source.count; ++k) c[k] = Vec3(source.polygon[k]);
            stratified_points(c.data(), source.count, grid, mix_seed(seed, uint32_t(source.element)), points.data());
            const double sample_weight = picks * (max_channel(source.radiance) / brightest) / double(grid * grid);
            for (int k = 0; k < grid * grid; ++k) {
                const Vec3 d = points[k] - origin;
                const float r2 = glm::dot(d, d);
                const double kernel = r2 > 0.0f ? double(std::max(0.0f, glm::dot(normal, d)) *
                                                         std::max(0.0f, -glm::dot(Vec3(source.normal), d))) /
                                                      (r2 * r2)
                                                : 0.0;
                const bool seen_clear = unhidden_from_surface(scene_.visibility, elements_, origin, normal, points[k],
                                                              Vec3(source.normal), scene_.scene_size);
                clear += seen_clear;
                ++cast;
                seen += sample_weight * kernel;
                if (seen_clear) visible += sample_weight * kernel;
            }
        };
        const double step = group.area / rays;
        if (group.whole) {  // the emitters the picks fall on, found among the run's sums of area
            const std::vector<double>& before = scene_.runs[group.run].area_before;
            for (auto end = before.begin() + 1;;) {
                end = std::upper_bound(end, before.end(), next_pick);
                if (end == before.end()) break;
                int picks = 0;
                for (; next_pick < *end; next_pick += step) ++picks;
                cast_at(group.first + std::size_t(end - before.begin() - 1), picks);
                ++end;
            }
        } else {
            double covered = 0.0;
            for (std::size_t i = group.first; i < group.last; ++i) {
                if (!groups.faces[i]) continue;
                covered += scene_.emitters[i].area;
                int picks = 0;
                for (; next_pick < covered; next_pick += step) ++picks;
                if (picks > 0) cast_at(i, picks);
            }
        }
        return seen > 0.0 ? visible / seen : cast > 0 ? double(clear) / cast : 1.0;
    }

    /// The solved radiance where a ray hit: the corner colours interpolation gives the element,
    /// blended at the hit (a smooth field; the element's flat value is off next to a seam). On the
    /// Cornell box at the Medium preset, 1.00% RMS from Cycles against 1.19% with flat values.
    Rgb radiance_near(const hr::Visibility::Hit& hit) const {
        const std::size_t h = std::size_t(hit.patch);
        if (elements_.is_back(h)) return scene_.radiance[h];  // not written, so no corner colours
        const Rgb blended = blend_corners(elements_, h, &corner_field_[4 * h], hit.u, hit.v);
        if (!has_bubbles(corner_field_, elements_)) return blended;
        return blended + element_bubble(elements_, h, hit.u, hit.v) * corner_field_[bubble_slot(elements_, h)];
    }

    /// What the light around the hit element's corners on seams adds (corner_wedges.h).
    Rgb wedge_light(const hr::Visibility::Hit& hit) const {
        if (wedges_ == nullptr || wedges_->empty()) return Rgb(0.0);
        return wedges_->correction(elements_, std::size_t(hit.patch), hit.u, hit.v);
    }

    /// Where the shadow and World rays from a point x on a surface of normal n leave
    /// (hr::Visibility::lifted).
    Vec3 lifted(const Vec3& x, const Vec3& n) const { return scene_.visibility.lifted(x, n); }

    /// Hits closer to the point than this times the square root of the hit element's area read a
    /// surface near it. The field there, blended from the element's corners, does not hold how the
    /// light changes across the element (a slot a centimetre wide beside a wall, a contact, a
    /// corner): those reads take the neighbouring points' gathered light, solved with theirs
    /// (solve_near_reads).
    static constexpr float kNear = 1.0f;

    const GatherScene& scene_;
    const Elements& elements_;
    const std::vector<Rgb>& corner_field_;
    const CornerWedges* wedges_;
    RayKeeping keeping_;
    int grid_, shadow_rays_;
};

}  // namespace

namespace {

/// Element vertices whose place (weld) is shared with an element of another plane: along a room's
/// edges, where a block stands on a floor. Rays from a point next to a seam meet the other surface
/// right at it, so they read its light there. `fronts`: only the elements that are not an emitting
/// polygon's back side count (where surfaces meet, not where an emitter's two sides do).
std::vector<uint8_t> seam_vertices(const Elements& elements, const std::vector<int32_t>& place, std::size_t places,
                                   bool fronts = false) {
    std::vector<int32_t> first_element(places, -1);
    std::vector<uint8_t> seam_place(places, 0);
    for (std::size_t e = 0; e < elements.size(); ++e)
        for (int k = 0; k < elements.corner_count(e) && !(fronts && elements.is_back(e)); ++k) {
            const std::size_t p = std::size_t(place[elements.corners[e][k]]);
            if (first_element[p] < 0)
                first_element[p] = int32_t(e);
            else if (glm::dot(elements.normal[e], elements.normal[std::size_t(first_element[p])]) < 0.99f)
                seam_place[p] = 1;
        }
    std::vector<uint8_t> seam(elements.vertices.size(), 0);
    for (std::size_t v = 0; v < seam.size(); ++v) seam[v] = seam_place[std::size_t(place[v])];
    return seam;
}

/// The field the output's rays read, gathered at every element vertex by `gatherer` from the
/// interpolated solution: each vertex's direct light exact (shadow edges placed by shadow rays at
/// the vertices, not by the hemi-cube's cells) and its indirect light from the solution one bounce
/// further away, where the solution's error counts times the reflectance. Buried vertices keep
/// their interpolated values. A vertex at a flat place takes the light of its place's lowest vertex
/// (flat_places.h: `same_place`), with its own element's reflectance and emission. `direct`: per
/// element vertex, the direct light found there where the field's point was not buried (the output
/// points' direct light, the same shadow rays from the same place).
template <typename PolygonCentre>
void gather_field(const Gatherer& gatherer, const Elements& elements, const std::vector<Rgb>& emitted,
                  const std::vector<int32_t>& element_at, const std::vector<int32_t>& same_place,
                  const std::vector<Vec3>& approach, const std::vector<int32_t>& place,
                  const PolygonCentre& polygon_centre, const ProgressFn& progress, std::vector<Rgb>& field,
                  std::vector<PointStatistics>& statistics, KnownDirectLight& direct) {
    std::vector<int32_t> vertices;
    for (std::size_t v = 0; v < elements.vertices.size(); ++v)
        if (element_at[v] >= 0 && same_place[v] == int32_t(v)) vertices.push_back(int32_t(v));
    std::vector<Rgb> value(elements.vertices.size()), light_at(elements.vertices.size());
    std::vector<uint8_t> done(elements.vertices.size(), 0), moved(elements.vertices.size(), 0);
    direct.light.assign(elements.vertices.size(), Rgb(0.0));
    direct.known.assign(elements.vertices.size(), 0);
    parallel_rows("gather field", vertices.size(), 16, 0, progress, [&](std::size_t t) {
        const std::size_t v = std::size_t(vertices[t]);
        const std::size_t e = std::size_t(element_at[v]);
        Rgb L, light;
        float near_share = 0.0f;
        if (gatherer.radiance_at(int32_t(v), e, polygon_centre(e), approach[v], uint32_t(place[v]), L, light,
                                 near_share, direct.light[v], false, {nullptr, &statistics[v], nullptr, &moved[v]}) &&
            std::isfinite(L.r) && std::isfinite(L.g) && std::isfinite(L.b)) {
            value[v] = L;
            light_at[v] = light;
            done[v] = 1;
        }
        return true;
    });
    for (std::size_t v = 0; v < elements.vertices.size(); ++v) {
        const std::size_t from = std::size_t(same_place[v]), e = std::size_t(std::max(element_at[v], 0));
        if (element_at[v] < 0 || !done[from]) continue;
        direct.light[v] = direct.light[from];
        direct.known[v] = !moved[from];
        if (from == v) continue;
        value[v] = emitted[e] + elements.reflectance[e] * light_at[from];
        statistics[v] = statistics[from];
        done[v] = 1;
    }
    for (std::size_t e = 0; e < elements.size(); ++e)
        for (int k = 0; k < elements.corner_count(e); ++k) {
            const std::size_t v = std::size_t(elements.corners[e][k]);
            if (done[v]) field[4 * e + k] = value[v];
        }
}

/// The distance from `point` to element e's polygon: over the polygon the distance to its plane, beside
/// it the way to its nearest edge as well.
double distance_to_element(const Elements& elements, std::size_t e, const glm::dvec3& point) {
    const glm::dvec3 normal(elements.normal[e]);
    const int count = elements.corner_count(e);
    const glm::dvec3 first(elements.vertices[std::size_t(elements.corners[e][0])]);
    const double height = glm::dot(normal, point - first);
    const glm::dvec3 foot = point - height * normal;
    bool inside = true;
    double beside = std::numeric_limits<double>::infinity();
    for (int k = 0; k < count; ++k) {
        const glm::dvec3 a(elements.vertices[std::size_t(elements.corners[e][k])]);
        const glm::dvec3 b(elements.vertices[std::size_t(elements.corners[e][(k + 1) % count])]);
        const glm::dvec3 edge = b - a;
        inside = inside && glm::dot(glm::cross(edge, foot - a), normal) >= 0.0;
        const double along = std::clamp(glm::dot(foot - a, edge) / std::max(glm::dot(edge, edge), 1e-300), 0.0, 1.0);
        beside = std::min(beside, glm::length(foot - (a + along * edge)));
    }
    return std::sqrt(height * height + (inside ? 0.0 : beside * beside));
}

/// Whether a point or spot lamp lies in front of element e (`size` from its centre to its farthest
/// corner) nearer to it than half its size: a lamp hung a few centimetres from a wall or inside a
/// fixture. The distance is to the element, not its centre: an element one of whose corners lies
/// under the lamp holds the lamp's peak there.
bool near_lamp(const Lights& lights, const Elements& elements, std::size_t e, double size) {
    const glm::dvec3 normal(elements.normal[e]), centre(elements.centre[e]);
    return std::any_of(lights.points.begin(), lights.points.end(), [&](const PointLight& lamp) {
        const glm::dvec3 position(lamp.position);
        const double near = 0.5 * size + double(lamp.radius);
        // The element lies within `size` of its centre: a lamp farther than that and `near` is not beside it.
        return glm::dot(normal, position - centre) > 0.0 && glm::length(position - centre) < size + near &&
               distance_to_element(elements, e, position) < near;
    });
}

/// Elements lit by an emitter or lamp nearer to them than half their size (a ceiling beside a panel
/// hung 1 cm under it, a wall beside a lamp): that light changes on the scale of the source's
/// distance, which the element's corners do not resolve (the vertex at the panel's edge holds half
/// its back side's light, the next vertex none, and the line between them is far too bright; a
/// corner next to a lamp holds its peak, the others almost nothing).
std::vector<std::size_t> near_lit_elements(const Elements& elements, const std::vector<Rgb>& emitted,
                                           const std::vector<EmitterRun>& runs, const Lights& lights) {
    std::vector<std::size_t> near;
    for (std::size_t e = 0; e < elements.size(); ++e) {
        if (elements.is_back(e) || max_channel(emitted[e]) > 0.0) continue;
        const glm::dvec3 centre(elements.centre[e]);
        const double size = circumradius(elements, int32_t(e));
        const bool near_lit = std::any_of(runs.begin(), runs.end(), [&](const EmitterRun& run) {
            const double distance = glm::dot(run.normal, centre - run.point);
            return distance > 0.0 && distance < 0.5 * size && glm::length(centre - run.centre) < run.radius + size;
        });
        if (near_lit || near_lamp(lights, elements, e, size)) near.push_back(e);
    }
    return near;
}

/// The field's corners of the `near` lit elements (near_lit_elements) scaled to the element's
/// solved light, which integrates the source over the element (the near field's exact area
/// factors, near_field.h; the lamps' exact mean over the element, lights.h). Whatever writes
/// gathered light into the field (the field's vertices, the output points after the first pass,
/// the seams' solve) keeps this, so that no later pass reads a lamp's peak spread over an element.
void keep_near_lit_elements_power(const Elements& elements, const std::vector<Rgb>& radiance,
                                  const std::vector<std::size_t>& near, std::vector<Rgb>& field) {
    for (const std::size_t e : near) {
        const int count = elements.corner_count(e);
        for (int c = 0; c < 3; ++c) {
            double sum = 0.0;
            for (int k = 0; k < count; ++k) sum += field[4 * e + std::size_t(k)][c];
            if (!(sum > 0.0) || !(radiance[e][c] >= 0.0)) continue;
            const double scale = radiance[e][c] * count / sum;
            for (int k = 0; k < count; ++k) field[4 * e + std::size_t(k)][c] *= scale;
        }
    }
}

/// Element vertices next to which the light turns with the direction from the vertex
/// (corner_wedges.h): where an occluder stands on a surface with a corner of its own (some plane's
/// elements around the place turn through more than half a turn: a floor around a block's foot,
/// three quarters), and along convex edges (a block's top and upright edges), whose faces hide each
/// other's surroundings. Along a room's edges and in its corners (concave: a half or a quarter turn)
/// the surfaces meet in straight lines and the light next to a vertex turns far less.
std::vector<uint8_t> turning_vertices(const Elements& elements, const std::vector<int32_t>& place, std::size_t places) {
    struct Plane {
        Vec3 normal, point;
        double turn;
    };
    std::vector<std::vector<Plane>> planes_at(places);
    for (std::size_t e = 0; e < elements.size(); ++e) {
        if (elements.is_back(e)) continue;
        const int count = elements.corner_count(e);
        for (int k = 0; k < count; ++k) {
            const Vec3 corner = elements.vertices[std::size_t(elements.corners[e][k])];
            const Vec3 next = elements.vertices[std::size_t(elements.corners[e][(k + 1) % count])] - corner;
            const Vec3 previous = elements.vertices[std::size_t(elements.corners[e][(k + count - 1) % count])] - corner;
            const float lengths = glm::length(next) * glm::length(previous);
            if (!(lengths > 0.0f)) continue;
            const double angle = std::acos(std::clamp(double(glm::dot(next, previous) / lengths), -1.0, 1.0));
            auto& planes = planes_at[std::size_t(place[std::size_t(elements.corners[e][k])])];
            auto same = std::find_if(planes.begin(), planes.end(), [&](const Plane& plane) {
                return glm::dot(plane.normal, elements.normal[e]) > 0.99f;
            });
            if (same == planes.end())
                planes.push_back({elements.normal[e], elements.centre[e], angle});
            else
                same->turn += angle;
        }
    }
    auto turning = [](const std::vector<Plane>& planes) {
        for (const Plane& a : planes) {
            if (a.turn > M_PI * (1.0 + 1e-3)) return true;  // a foot
            for (const Plane& b : planes)                   // convex: b's element lies behind a's plane
                if (&a != &b && glm::dot(a.normal, b.point - a.point) < -1e-3f * glm::length(b.point - a.point))
                    return true;
        }
        return false;
    };
    std::vector<uint8_t> at_place(places, 0);
    for (std::size_t p = 0; p < places; ++p) at_place[p] = planes_at[p].size() > 1 && turning(planes_at[p]);
    std::vector<uint8_t> turns(elements.vertices.size(), 0);
    for (std::size_t v = 0; v < turns.size(); ++v) turns[v] = at_place[std::size_t(place[v])];
    return turns;
}

/// The light around the element corners on seams (corner_wedges.h), by `gatherer`: at each table
/// point, how much more light arrives there than at the point the vertex is gathered at. The direct
/// light's change along the same shadow rays (Gatherer::direct_change), the indirect light's along
/// the same gather rays, so that what the field holds in common cancels.
/// The indirect light turns slowly around a vertex: it is gathered at every fourth table point,
/// linear in between.
CornerWedges wedge_tables(const Gatherer& gatherer, const Elements& elements, const std::vector<uint8_t>& seam,
                          const std::vector<int32_t>& place, const std::vector<int32_t>& element_at,
                          const std::vector<Vec3>& approach, float scene_size, const ProgressFn& progress) {
    constexpr int kEvery = 4, kIndirect = CornerWedges::kBins / kEvery;
    auto fill = [&](std::size_t e, int k, const Vec3* table_points, Rgb* table) {
        const int32_t v = elements.corners[e][k];
        const std::size_t gathered_in = std::size_t(element_at[v]);
        const uint32_t seed = uint32_t(place[std::size_t(v)]);
        const Vec3 vertex_point = gatherer.first_point(v, gathered_in, approach[std::size_t(v)]);
        const DirectParts at_vertex_direct = gatherer.direct_at(vertex_point, gathered_in, seed);
        Rgb at_vertex(0.0), there(0.0);
        std::array<Rgb, kIndirect> more{};
        if (gatherer.indirect_near(vertex_point, gathered_in, seed, at_vertex))
            for (int j = 0; j < kIndirect; ++j)
                if (gatherer.indirect_near(table_points[kEvery * j + kEvery / 2], e, seed, there))
                    more[std::size_t(j)] = there - at_vertex;
        for (int i = 0; i < CornerWedges::kBins; ++i) {
            const double position = std::clamp((i - kEvery / 2) / double(kEvery), 0.0, kIndirect - 1.0);
            const int low = std::min(int(position), kIndirect - 2);
            const double t = position - low;
            table[i] = gatherer.direct_change(at_vertex_direct, table_points[i], e, seed) +
                       (1.0 - t) * more[std::size_t(low)] + t * more[std::size_t(low + 1)];
        }
    };
    return CornerWedges(elements, seam, scene_size, fill, [&](std::size_t count, const auto& body) {
        parallel_rows("gather wedges", count, 16, 0, progress, [&](std::size_t t) {
            body(t);
            return true;
        });
    });
}

/// The element vertices gathered, each once, with one element around it: those holding input
/// corners (the output) and those on seams (read by the output's rays).
struct GatherPoints {
    std::vector<int32_t> element_at;  ///< per element vertex: the element it is gathered in (-1: none)
    std::vector<uint8_t> is_output;   ///< per element vertex: it holds an input corner
    std::vector<int32_t> points;      ///< the element vertices gathered
};

GatherPoints gather_points(const Elements& elements, const std::vector<uint8_t>& seam) {
    GatherPoints g{
        std::vector<int32_t>(elements.vertices.size(), -1), std::vector<uint8_t>(elements.vertices.size(), 0), {}};
    for (std::size_t e = elements.size(); e-- > 0;)
        for (int k = 0; k < elements.corner_count(e); ++k) g.element_at[elements.corners[e][k]] = int32_t(e);
    for (const int32_t v : elements.corner_vertex)
        if (v >= 0 && g.element_at[v] >= 0) g.is_output[v] = 1;
    for (std::size_t v = 0; v < elements.vertices.size(); ++v)
        if (g.element_at[v] >= 0 && (g.is_output[v] || seam[v])) g.points.push_back(int32_t(v));
    return g;
}

/// Each element's polygon's centre (its elements' centres, area-weighted), where points buried at
/// their element are moved towards.
class PolygonCentres {
public:
    explicit PolygonCentres(const Elements& elements) : elements_(elements) {
        for (std::size_t e = 0; e < elements.size(); ++e) {
            const std::size_t p = std::size_t(elements.polygon[e]);
            if (p >= sum_.size()) {
                sum_.resize(p + 1, glm::dvec3(0.0));
                area_.resize(p + 1, 0.0);
            }
            sum_[p] += double(elements.area[e]) * glm::dvec3(elements.centre[e]);
            area_[p] += double(elements.area[e]);
        }
    }
    Vec3 operator()(std::size_t e) const {
        const std::size_t p = std::size_t(elements_.polygon[e]);
        return area_[p] > 0.0 ? Vec3(sum_[p] / area_[p]) : elements_.centre[e];
    }

private:
    const Elements& elements_;
    std::vector<glm::dvec3> sum_;
    std::vector<double> area_;
};

/// Solves the light of the points whose rays met surfaces near them, each linear in the field at
/// the vertices those rays read (NearReads), by Jacobi sweeps until no value changes by more than
/// 1e-6 of the largest (at most 200 sweeps): the same as gathering those points again and again
/// from each other's values.
template <typename WriteField>
void solve_near_reads(const Elements& elements, const std::vector<Rgb>& emitted, const std::vector<int32_t>& points,
                      const std::vector<int32_t>& element_at, const std::vector<NearReads>& reads,
                      const std::vector<uint8_t>& recorded, std::vector<Rgb>& field, std::vector<Rgb>& value,
                      std::vector<Rgb>& light, const WriteField& write_field) {
    for (int sweep = 0; sweep < 200; ++sweep) {
        double change = 0.0, largest = 0.0;
        for (std::size_t i = 0; i < points.size(); ++i) {
            if (!recorded[i]) continue;
            const std::size_t e = std::size_t(element_at[points[i]]);
            Rgb indirect = reads[i].indirect;
            for (const auto& [slot, weight] : reads[i].slots) indirect += weight * field[std::size_t(slot)];
            light[i] = reads[i].direct + glm::max(indirect, Rgb(0.0));
            const Rgb L = emitted[e] + elements.reflectance[e] * light[i];
            change = std::max(change, max_channel(glm::abs(L - value[i])));
            largest = std::max(largest, max_channel(L));
            value[i] = L;
        }
        write_field(recorded);
        if (change <= 1e-6 * largest) break;
    }
}

/// The wall clock and the rays traced (GatherCost), read phase by phase.
class PhaseMeter {
public:
    PhaseMeter(const hr::Visibility& visibility, const hr::Visibility* back_sides)
        : visibility_(visibility), back_sides_(back_sides), start_(Clock::now()), rays_(traced()) {}
    /// Adds the seconds and rays since the last call (or the start) to `phase`.
    void add_to(GatherPhaseCost& phase) {
        const Clock::time_point now = Clock::now();
        const std::uint64_t rays = traced();
        phase.seconds += std::chrono::duration<double>(now - start_).count();
        phase.rays += rays - rays_;
        start_ = now;
        rays_ = rays;
    }

private:
    using Clock = std::chrono::steady_clock;
    std::uint64_t traced() const {
        return visibility_.rays_traced() + (back_sides_ != nullptr ? back_sides_->rays_traced() : 0);
    }
    const hr::Visibility& visibility_;
    const hr::Visibility* back_sides_;
    Clock::time_point start_;
    std::uint64_t rays_;
};

/// The output points whose indirect light is read from gathered ones (irradiance_cache.h): per
/// gathered point (GatherPoints::points), the records it reads (point, weight; none: it gathers its
/// own), and where each output point is gathered.
struct SharedLight {
    std::vector<std::vector<std::pair<int32_t, double>>> from;
    std::vector<CachePoint> at;
    std::vector<uint8_t> read;  ///< per point: a record some interpolated point reads (with its gradients)
    bool interpolated(std::size_t i) const { return !from.empty() && !from[i].empty(); }
    bool gradients_read(std::size_t i) const { return !read.empty() && read[i] != 0; }
};

/// Probe rays per output point for its records' harmonic mean distance.
constexpr int kProbeRays = 64;

/// Which output points gather (irradiance_cache.h plan_cache), from their probe rays: those at
/// `keep_vertex` (seams, turning vertices), those whose probe met a back face (maybe buried) or a
/// surface nearer than their element's size (a contact), and the records; `accuracy` <= 0: all.
/// The points at one flat place (`same_place`, flat_places.h) share one probe: the same place, the
/// same plane, the same seeds.
SharedLight share_light(const Gatherer& gatherer, const Elements& elements, const GatherPoints& gathered,
                        const std::vector<Vec3>& approach, const std::vector<int32_t>& place,
                        const std::vector<int32_t>& same_place, const std::vector<uint8_t>& keep_vertex,
                        double accuracy, float scene_size, const ProgressFn& progress) {
    SharedLight shared;
    if (!(accuracy > 0.0)) return shared;
    const std::vector<int32_t>& points = gathered.points;
    std::vector<int32_t> output;
    for (std::size_t i = 0; i < points.size(); ++i)
        if (gathered.is_output[std::size_t(points[i])]) output.push_back(int32_t(i));
    auto vertex_of = [&](std::size_t c) { return points[std::size_t(output[c])]; };
    auto element_of = [&](std::size_t c) { return std::size_t(gathered.element_at[std::size_t(vertex_of(c))]); };
    std::vector<int64_t> prober(same_place.size(), -1);  // per vertex standing for a place: its output point probed
    std::vector<std::size_t> probed;
    for (std::size_t c = 0; c < output.size(); ++c) {
        int64_t& first = prober[std::size_t(same_place[std::size_t(vertex_of(c))])];
        if (first < 0) {
            first = int64_t(c);
            probed.push_back(c);
        }
    }
    std::vector<Probe> probes(output.size());
    parallel_rows("gather probes", probed.size(), 16, 0, progress, [&](std::size_t t) {
        const std::size_t c = probed[t];
        const int32_t v = vertex_of(c);
        probes[c] = gatherer.probe(v, element_of(c), approach[std::size_t(v)], uint32_t(place[std::size_t(v)]),
                                   kProbeRays, scene_size);
        return true;
    });
    std::vector<CachePoint> cache(output.size());
    for (std::size_t c = 0; c < output.size(); ++c) {
        const int32_t v = vertex_of(c);
        const std::size_t e = element_of(c);
        const Probe& probe = probes[std::size_t(prober[std::size_t(same_place[std::size_t(v)])])];
        const bool contact = probe.nearest < std::sqrt(double(elements.area[e]));
        cache[c] = {glm::dvec3(gatherer.first_point(v, e, approach[std::size_t(v)])), glm::dvec3(elements.normal[e]),
                    probe.harmonic_distance,
                    keep_vertex[std::size_t(v)] || probe.back_face || contact ||
                        gatherer.covered(v, e, approach[std::size_t(v)])};
    }
    const CachePlan plan = plan_cache(cache, accuracy);
    shared.from.resize(points.size());
    shared.at.resize(points.size());
    shared.read.assign(points.size(), 0);
    for (std::size_t c = 0; c < output.size(); ++c) {
        shared.at[std::size_t(output[c])] = cache[c];
        for (const auto& [record, weight] : plan.from[c]) {
            shared.from[std::size_t(output[c])].emplace_back(output[std::size_t(record)], weight);
            shared.read[std::size_t(output[std::size_t(record)])] = 1;
        }
    }
    return shared;
}

/// The gathered points' values, light and statistics, and each one's direct light and gradients.
struct PointValues {
    std::vector<Rgb> value, light, direct;
    std::vector<LightGradients> gradients;
    std::vector<uint8_t> done;
    std::vector<PointStatistics> statistics;
};

/// The interpolated points' light: their own direct light plus the indirect light read from the
/// gathered records (light - direct) with their gradients, weighted over those gathered. A point
/// whose records all failed is left undone (buried). Its statistics: the records' sampling
/// variance and probe read, as the weighted mean is.
void read_shared(const SharedLight& shared, const Elements& elements, const std::vector<Rgb>& emitted,
                 const GatherPoints& gathered, PointValues& p) {
    for (std::size_t i = 0; i < shared.from.size(); ++i) {
        if (!shared.interpolated(i)) continue;
        double total = 0.0;
        for (const auto& [r, weight] : shared.from[i]) total += p.done[std::size_t(r)] ? weight : 0.0;
        p.done[i] = total > 0.0;
        if (!p.done[i]) continue;
        Rgb indirect(0.0), variance(0.0), probe_read(0.0);
        for (const auto& [r, weight] : shared.from[i]) {
            const std::size_t k = std::size_t(r);
            if (!p.done[k]) continue;
            const double w = weight / total;
            indirect += w * read_record(shared.at[k], p.light[k] - p.direct[k], p.gradients[k], shared.at[i]);
            variance += w * w * p.statistics[k].variance;
            probe_read += w * p.statistics[k].probe_read;
        }
        const std::size_t e = std::size_t(gathered.element_at[std::size_t(gathered.points[i])]);
        p.light[i] = glm::max(p.direct[i] + indirect, Rgb(0.0));
        p.value[i] = emitted[e] + elements.reflectance[e] * p.light[i];
        p.statistics[i].indirect = indirect;
        p.statistics[i].variance = variance;
        p.statistics[i].probe_read = probe_read;
    }
}

/// Per output point, the point whose direct light it takes: an interpolated point at a flat place
/// (flat_places.h) the first interpolated point there (in the order of `gathered.points`); any other
/// point itself.
std::vector<std::size_t> shared_direct_light(const GatherPoints& gathered, const SharedLight& shared,
                                             const std::vector<int32_t>& same_place) {
    const std::vector<int32_t>& points = gathered.points;
    std::vector<std::size_t> from(points.size());
    std::vector<int64_t> first_at(same_place.size(), -1);  // per element vertex standing for a place
    for (std::size_t i = 0; i < points.size(); ++i) {
        from[i] = i;
        if (!shared.interpolated(i)) continue;
        int64_t& first = first_at[std::size_t(same_place[std::size_t(points[i])])];
        if (first < 0)
            first = int64_t(i);
        else
            from[i] = std::size_t(first);
    }
    return from;
}

/// Output corners whose point, where Cycles bakes them, lies inside other geometry (a face running
/// on under a wall, into a beam or a brush, or lying on another face) were gathered from a point
/// moved to the visible side, which the field and the seams read, or not at all where every point
/// was buried. What the corner shows is what Cycles bakes there: the light at that point, nearly
/// none inside a closed solid, which both bakes then interpolate across the face alike.
void bake_buried_corners_as_cycles(const Gatherer& gatherer, const GatherPoints& gathered,
                                   const std::vector<uint8_t>& moved, const std::vector<Vec3>& approach,
                                   const std::vector<int32_t>& place, const ProgressFn& progress, PointValues& p) {
    const std::vector<int32_t>& points = gathered.points;
    std::vector<std::size_t> buried;
    for (std::size_t i = 0; i < points.size(); ++i)
        if ((moved[i] || !p.done[i]) && gathered.is_output[std::size_t(points[i])]) buried.push_back(i);
    parallel_rows("gather buried corners", buried.size(), 4, 0, progress, [&](std::size_t t) {
        const std::size_t i = buried[t];
        const std::size_t v = std::size_t(points[i]);
        Rgb L, H;
        if (gatherer.buried_at_corner(points[i], std::size_t(gathered.element_at[v]), approach[v], uint32_t(place[v]),
                                      L, H) &&
            std::isfinite(L.r + L.g + L.b + H.r + H.g + H.b)) {
            p.value[i] = L;
            p.light[i] = H;
            p.done[i] = 1;
        }
        return true;
    });
}

}  // namespace

GatherCost final_gather(const Elements& elements, const std::vector<Rgb>& emitted, const std::vector<Rgb>& radiance,
                        const Lights& lights, const WorldLight& world, const FinalGatherSettings& settings,
                        const int32_t* material, const int32_t* face_offsets, std::size_t face_count,
                        float hard_edge_angle, CornerColors& colors, CornerColors& light_colors,
                        const ProgressFn& progress, GatherStatistics* statistics, const GatherKept& kept) {
    GatherCost cost;
    if (elements.size() == 0) return cost;
    const auto started = std::chrono::steady_clock::now();
    const std::vector<Vec3> approach = corner_approach(elements, face_offsets, face_count);
    std::size_t places = 0;
    const std::vector<int32_t> place = weld_points(elements.vertices, weld_tolerance(elements.vertices), places);
    const std::vector<uint8_t> seam = seam_vertices(elements, place, places);

    const GatherPoints gathered = gather_points(elements, seam);
    const std::vector<int32_t>&element_at = gathered.element_at, &points = gathered.points;
    const std::vector<uint8_t>& is_output = gathered.is_output;
    const float scene_size = scene_diagonal(elements.vertices);
    const hr::Visibility visibility(elements.vertices, ray_corners(elements, false), scene_size);
    std::optional<hr::Visibility> backs;
    if (std::any_of(elements.side.begin(), elements.side.end(), [](uint8_t s) { return s == Elements::kBack; }))
        backs.emplace(elements.vertices, ray_corners(elements, true), scene_size);
    const hr::Visibility* back_sides = backs ? &*backs : nullptr;
    const CoincidentFaces coincident(elements, 2e-6f * scene_size);
    const std::vector<Emitter> emitters = emitting_elements(elements, emitted);
    const std::vector<EmitterRun> runs = emitter_runs(elements, emitters);
    const WorldSampler world_sampler(world);
    const GatherScene scene{elements,      emitted,    radiance,   lights,
                            world_sampler, emitters,   runs,       visibility,
                            back_sides,    coincident, scene_size, source_signatures(lights, world),
                            kept};
    const PolygonCentres polygon_centre(elements);
    const std::vector<uint8_t> turning = turning_vertices(elements, place, places);
    const std::vector<int32_t> same_place = flat_place_vertices(elements, place, places, seam, turning);
    PhaseMeter meter(visibility, back_sides);
    cost.other.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();

    // The first pass reads the interpolated solution, or the field gathered from it. Points whose rays met a surface
    // near them (within the size of the element hit) read the field where it is least like the light: a room's corner
    // is half lit by the walls' light at the corner, and a wall beside a slot a centimetre wide reads the slot's floor,
    // whose field the solution's elements leave lit where the wall shades it. The second pass gathers those points
    // again from the first pass's values, keeping what they read near them as weights. Then their light is solved: each
    // is linear in the field at the vertices it read near it, which are such points too (solve_near_reads). Passes
    // alone converge slowly where two or three surfaces meet: a room's corner sees the other two walls' corner light in
    // three quarters of its hemisphere.
    std::vector<Rgb> field = colors.element_corner;
    const std::vector<std::size_t> near_lit = near_lit_elements(elements, emitted, runs, lights);
    CornerWedges wedges;
    std::vector<PointStatistics> field_statistics(settings.field_rays > 0 ? elements.vertices.size() : 0);
    KnownDirectLight field_direct;
    std::vector<Rgb> field_error;  // the statistics' field_power_error
    if (settings.field_rays > 0) {
        FinalGatherSettings field_settings = settings;
        field_settings.rays = settings.field_rays;
        const Gatherer field_gatherer(scene, colors.element_corner, field_settings);
        gather_field(field_gatherer, elements, emitted, element_at, same_place, approach, place, polygon_centre,
                     progress, field, field_statistics, field_direct);
        // The lamps' light the corners' blend misses; then, before the near lit elements' corners are
        // scaled, how far their corners' light was from it tells how little of its shape they hold.
        append_bubbles(elements,
                       lamp_bubbles(elements, lights, visibility, near_lit, kept.direct, scene.signatures, progress),
                       field);
        field_error = field_power_error(elements, field, radiance);
        keep_near_lit_elements_power(elements, radiance, near_lit, field);
        meter.add_to(cost.field);
        // The wedges: four times the field's rays, and a quarter of the shadow rays at each table
        // point (along the same shadow rays as at the vertex, the change has little noise).
        FinalGatherSettings wedge_settings = settings;
        wedge_settings.rays = 4 * settings.field_rays;
        wedge_settings.shadow_rays = std::max(1, settings.shadow_rays / 4);
        const Gatherer wedge_gatherer(scene, field, wedge_settings);
        wedges = wedge_tables(wedge_gatherer, elements, turning, place, element_at, approach, scene_size, progress);
        meter.add_to(cost.wedges);
    } else {
        field_error = field_power_error(elements, field, radiance);  // the interpolated solution, unscaled
    }
    std::vector<Rgb> probe = noise_probe(elements, field_statistics, place);
    // Each point's direct light comes from the first pass.
    PointValues p{std::vector<Rgb>(points.size(), Rgb(0.0)),
                  std::vector<Rgb>(points.size(), Rgb(0.0)),
                  std::vector<Rgb>(points.size(), Rgb(0.0)),
                  std::vector<LightGradients>(points.size()),
                  std::vector<uint8_t>(points.size(), 0),
                  std::vector<PointStatistics>(points.size(), {field_statistics.empty() ? nullptr : &probe})};
    std::vector<Rgb>&value = p.value, &light = p.light, &direct = p.direct;
    std::vector<uint8_t>& done = p.done;
    std::vector<PointStatistics>& point_statistics = p.statistics;
    std::vector<uint8_t> recorded(points.size(), 0), moved(points.size(), 0);
    std::vector<float> near_share(points.size(), 0.0f);
    std::vector<NearReads> reads(points.size());
    std::vector<std::size_t> todo(points.size());
    for (std::size_t i = 0; i < todo.size(); ++i) todo[i] = i;
    auto write_field = [&](const std::vector<uint8_t>& which) {  // the field at those points' vertices
        std::vector<int32_t> gathered_index(elements.vertices.size(), -1);
        for (std::size_t i = 0; i < points.size(); ++i)
            if (which[i]) gathered_index[points[i]] = int32_t(i);
        for (std::size_t e = 0; e < elements.size(); ++e)
            for (int k = 0; k < elements.corner_count(e); ++k) {
                const int32_t i = gathered_index[elements.corners[e][k]];
                if (i < 0) continue;
                field[4 * e + k] = value[std::size_t(i)];
                probe[4 * e + k] = Rgb(0.0);  // the gathered value: not the field's noise
            }
        keep_near_lit_elements_power(elements, radiance, near_lit, field);
    };
    // Seam vertices that hold no input corner are read by the output's rays only where those land
    // beside a seam, many of them at once: a field's share of rays each (four times its rays).
    FinalGatherSettings seam_settings = settings;
    if (settings.field_rays > 0) seam_settings.rays = std::min(settings.rays, 4 * settings.field_rays);
    std::vector<uint8_t> keep_vertex = seam_vertices(elements, place, places, true);
    for (std::size_t v = 0; v < keep_vertex.size(); ++v) keep_vertex[v] |= turning[v];
    const SharedLight shared = share_light(Gatherer(scene, field, settings), elements, gathered, approach, place,
                                           same_place, keep_vertex, settings.cache_accuracy, scene_size, progress);
    meter.add_to(cost.probes);
    const std::vector<std::size_t> direct_from = shared_direct_light(gathered, shared, same_place);
    const int passes = 2;
    for (int pass = 0; pass < passes && !todo.empty(); ++pass) {
        const bool last = pass + 1 == passes;
        const Gatherer gatherer(scene, field, settings, &wedges, RayKeeping::Folded);
        const Gatherer seam_gatherer(scene, field, seam_settings, &wedges, RayKeeping::Folded);
        parallel_rows(pass == 0 ? "gather" : "gather near surfaces", todo.size(), 4, 0, progress, [&](std::size_t t) {
            const std::size_t i = todo[t];
            const std::size_t e = std::size_t(element_at[points[i]]);
            const bool direct_known = pass > 0 || field_direct.at(points[i]);
            if (pass == 0 && direct_known) direct[i] = field_direct.light[std::size_t(points[i])];
            if (shared.interpolated(i)) {  // its direct light only; its indirect is read below
                if (direct_from[i] == i && !direct_known)
                    direct[i] = gatherer.direct_light(points[i], e, approach[std::size_t(points[i])],
                                                      uint32_t(place[points[i]]));
                return true;
            }
            Rgb L, H;
            float share = 0.0f;
            if ((is_output[points[i]] ? gatherer : seam_gatherer)
                    .radiance_at(points[i], e, polygon_centre(e), approach[std::size_t(points[i])],
                                 uint32_t(place[points[i]]), L, H, share, direct[i], direct_known,
                                 {last ? &reads[i] : nullptr, &point_statistics[i],
                                  shared.gradients_read(i) ? &p.gradients[i] : nullptr, &moved[i]}) &&
                std::isfinite(L.r) && std::isfinite(L.g) && std::isfinite(L.b) && std::isfinite(H.r) &&
                std::isfinite(H.g) && std::isfinite(H.b)) {
                value[i] = L;
                light[i] = H;
                done[i] = 1;
                recorded[i] = last;
                near_share[i] = share;
            }
            return true;
        });
        // The field at gathered vertices becomes their gathered light; next, the points whose rays
        // met a surface near them.
        if (pass == 0) {
            for (std::size_t i = 0; i < points.size(); ++i) direct[i] = direct[direct_from[i]];
            read_shared(shared, elements, emitted, gathered, p);
        }
        write_field(done);
        meter.add_to(pass == 0 ? cost.points : cost.seams);
        todo.clear();
        for (std::size_t i = 0; i < points.size(); ++i)
            if (done[i] && near_share[i] > 0.0f) todo.push_back(i);
    }
    solve_near_reads(elements, emitted, points, element_at, reads, recorded, field, value, light, write_field);
    read_shared(shared, elements, emitted, gathered, p);  // from the records' light after the solve
    meter.add_to(cost.seams);
    bake_buried_corners_as_cycles(Gatherer(scene, field, settings, &wedges, RayKeeping::Folded), gathered, moved,
                                  approach, place, progress, p);
    meter.add_to(cost.points);

    // Every slot on a gathered output vertex takes its value (where a smooth surface bends, the
    // mean of its faces'); points whose light is not finite keep the interpolated colour.
    std::vector<int32_t> output_index(elements.vertices.size(), -1);
    for (std::size_t i = 0; i < points.size(); ++i)
        if (is_output[points[i]]) output_index[points[i]] = int32_t(i);
    std::vector<Rgb> slot_value(4 * elements.size(), Rgb(0.0)), slot_light(4 * elements.size(), Rgb(0.0));
    std::vector<uint8_t> known(4 * elements.size(), 0);
    std::vector<int32_t> slot_point(4 * elements.size(), -1);
    for (std::size_t e = 0; e < elements.size(); ++e)
        for (int k = 0; k < elements.corner_count(e); ++k) {
            const int32_t i = output_index[elements.corners[e][k]];
            if (i < 0 || !done[std::size_t(i)]) continue;
            slot_value[4 * e + k] = value[std::size_t(i)];
            slot_light[4 * e + k] = light[std::size_t(i)];
            known[4 * e + k] = 1;
            slot_point[4 * e + k] = i;
        }
    if (statistics != nullptr)
        *statistics = gather_statistics(elements, material, hard_edge_angle, known, slot_point, point_statistics,
                                        light_colors, field_error, radiance, emitted);
    replace_corners(elements, material, hard_edge_angle, slot_value, known, colors);
    replace_corners(elements, material, hard_edge_angle, slot_light, known, light_colors);
    for (std::size_t i = 0; i < points.size(); ++i)
        if (is_output[points[i]])
            (!done[i] ? cost.buried : shared.interpolated(i) ? cost.interpolated : cost.gathered) += 1;
    meter.add_to(cost.other);
    return cost;
}

}  // namespace radiosity::detail
