/// @file gather_statistics.h
/// @brief What the final gather found at each output corner besides its colour: the numbers the
/// bake's error estimate is made of (the add-on's engine/error_estimate.py).
#pragma once

#include "geometry/scene.h"
#include "visibility/ray_tracer.h"

#include <vector>

namespace radiosity {

/// Per output corner, in radiance (the light times the corner's reflectance), placed on the corners
/// as the gathered colours are (replace_corners); zero on corners the gather left interpolated.
struct GatherStatistics {
    /// The light arriving at the corners (irradiance / pi, BakeResult::light_colors) as the solution
    /// gave it, interpolated, before the gather replaced it: apart from textures and emission.
    CornerColors solution_light;
    /// The indirect light the corner's rays read: the share of its colour that comes from the solution.
    CornerColors indirect;
    /// The variance of the corner's colour from its own indirect rays' sampling.
    CornerColors variance;
    /// The variance the noise of the field its rays read (FinalGatherSettings::field_rays) gives the
    /// corner's colour: one sample of it, detail::PointStatistics; 0 without a field.
    CornerColors field_noise;
    /// Per element: the light the field the rays read carries on it less the light the solve found
    /// there (detail::field_power_error), and that light, its solved radiance less its own emission.
    std::vector<Rgb> element_field_error, element_reflected;
};

namespace detail {

/// One gathered point's statistics: its indirect light (irradiance / pi, before its reflectance),
/// that light's sampling variance, and what its rays read of a probe field.
///
/// The probe measures how the field's own noise reaches the point. The field gathered at the
/// element vertices with few rays is noisy at each vertex, independently from vertex to vertex;
/// the point's rays average it over the vertices they reach, with weights w_v it does not keep.
/// Read through the same rays, a field of random signs z_v times each vertex's noise s_v gives
/// X = sum w_v z_v s_v, whose mean square over the signs is sum w_v^2 s_v^2: the variance the
/// field's noise gives the point (a trace estimated by random signs, Hutchinson 1990).
struct PointStatistics {
    const std::vector<Rgb>* probe = nullptr;  ///< the probe field, 4 an element as the field (none: not read)
    Rgb indirect{0.0}, variance{0.0}, probe_read{0.0};
};

/// Which half ray `ray` of a gather of `grid` x `grid` rays is in (RaySpread): +1 or -1, a checkerboard.
inline double half_sign(int ray, int grid) { return ((ray % grid) + (ray / grid)) % 2 == 0 ? 1.0 : -1.0; }

/// A point's statistics from its indirect light, the difference of its rays' halves' sums, the sum
/// of the probe field they read and their count (RaySpread::finish).
void spread_statistics(const Rgb& indirect, const Rgb& difference, const Rgb& probe, int rays,
                       PointStatistics& statistics);

/// The sampling variance of a stratified mean from its own samples, by two interpenetrating
/// half-samples (Mahalanobis 1946; the random group method, Wolter, Introduction to Variance
/// Estimation, 2007, ch. 2): the strata of the gather's grid split as a checkerboard, each half a
/// stratified estimate over the whole hemisphere, the mean's variance about (mean_a - mean_b)^2 / 4.
/// One such sample is a rough variance at one point; over many points it is a good one. Reads the
/// probe field (PointStatistics) at the same hits.
class RaySpread {
public:
    /// Writes into `statistics` at finish() (nothing when it is null); `grid`: the rays' strata a row.
    RaySpread(const Elements& elements, PointStatistics* statistics, int grid)
        : elements_(elements), statistics_(statistics), grid_(grid) {}
    /// Ray `ray`'s sample where it hit a front face; rays never added count as 0 (misses and back
    /// faces bring nothing).
    void add(int ray, const Rgb& sample, const hr::Visibility::Hit& hit);
    /// The point's indirect light, the mean of its `rays` samples.
    void finish(const Rgb& indirect, int rays) const;

private:
    const Elements& elements_;
    PointStatistics* statistics_;
    int grid_;
    Rgb difference_{0.0};  ///< the sum over one half less the other's
    Rgb probe_{0.0};       ///< the sum of the probe read
};

/// The probe field (PointStatistics): per element corner slot, a random sign of the vertex's place
/// (vertices at one place share their rays, so their noise) times the field's noise there, the
/// element's reflectance times the square root of `field_point`'s variance at its vertex.
std::vector<Rgb> noise_probe(const Elements& elements, const std::vector<PointStatistics>& field_point,
                             const std::vector<int32_t>& place);

/// Per element, the mean over it of `field` (its corners' values blended over it as the rays read
/// them, and its bubble where the field carries bubbles: corner_blend.h) less its solved `radiance`: where it is not 0,
/// the field does not carry the light the solve found there (a lamp's hot spot between the vertices, flattened by
/// interpolation or missed by the vertices' gather). The solve's light on an element is exact for the lamps (their flux
/// is kept element by element, lights.h). 0 on emitters' back sides, which the rays read as solved.
std::vector<Rgb> field_power_error(const Elements& elements, const std::vector<Rgb>& field,
                                   const std::vector<Rgb>& radiance);

/// The statistics at the output corners. `known` and `slot_point`: per element corner slot (4 an
/// element), whether the gather wrote it and which gathered point's values it took; `point`: each
/// gathered point's; `solution_light`: the interpolated light arriving before the gather;
/// `field_error`: the field's field_power_error (on elements whose corners the gather scales to
/// their solved light beside a lamp or emitter, as the gathered corners had it before: their shape
/// within the element is no better known than that); `radiance` and `emitted`: each element's solved
/// radiance and own emission.
GatherStatistics gather_statistics(const Elements& elements, const int32_t* material, float hard_edge_angle,
                                   const std::vector<uint8_t>& known, const std::vector<int32_t>& slot_point,
                                   const std::vector<PointStatistics>& point, const CornerColors& solution_light,
                                   const std::vector<Rgb>& field_error, const std::vector<Rgb>& radiance,
                                   const std::vector<Rgb>& emitted);

}  // namespace detail
}  // namespace radiosity
