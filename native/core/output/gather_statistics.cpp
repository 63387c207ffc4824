/// @file gather_statistics.cpp
/// @brief The final gather's statistics at the output corners (gather_statistics.h).
#include "output/gather_statistics.h"

#include "common/stratified.h"
#include "output/corner_blend.h"
#include "output/interpolation.h"
#include "output/lamp_bubbles.h"

#include <algorithm>

namespace radiosity::detail {

void RaySpread::add(int ray, const Rgb& sample, const hr::Visibility::Hit& hit) {
    if (statistics_ == nullptr) return;
    difference_ += half_sign(ray, grid_) * sample;
    const std::size_t h = std::size_t(hit.patch);
    if (statistics_->probe == nullptr || elements_.is_back(h)) return;  // a back side reads its solved value
    probe_ += blend_corners(elements_, h, &(*statistics_->probe)[4 * h], hit.u, hit.v);
}

void RaySpread::finish(const Rgb& indirect, int rays) const {
    if (statistics_ != nullptr) spread_statistics(indirect, difference_, probe_, rays, *statistics_);
}

void spread_statistics(const Rgb& indirect, const Rgb& difference, const Rgb& probe, int rays,
                       PointStatistics& statistics) {
    if (rays <= 0) return;
    statistics.indirect = indirect;
    // mean_a - mean_b = 2 difference / rays, a quarter of its square.
    statistics.variance = difference * difference / (double(rays) * double(rays));
    statistics.probe_read = probe / double(rays);
}

std::vector<Rgb> noise_probe(const Elements& elements, const std::vector<PointStatistics>& field_point,
                             const std::vector<int32_t>& place) {
    std::vector<Rgb> probe(4 * elements.size(), Rgb(0.0));
    if (field_point.empty()) return probe;
    for (std::size_t e = 0; e < elements.size(); ++e)
        for (int k = 0; k < elements.corner_count(e); ++k) {
            const std::size_t v = std::size_t(elements.corners[e][k]);
            const double sign = (mix_seed(uint32_t(place[v]), 0x9B0BEU) & 1U) != 0U ? 1.0 : -1.0;
            probe[4 * e + std::size_t(k)] = sign * elements.reflectance[e] * glm::sqrt(field_point[v].variance);
        }
    return probe;
}

std::vector<Rgb> field_power_error(const Elements& elements, const std::vector<Rgb>& field,
                                   const std::vector<Rgb>& radiance) {
    std::vector<Rgb> error(elements.size(), Rgb(0.0));
    for (std::size_t e = 0; e < elements.size(); ++e) {
        if (elements.is_back(e)) continue;  // read as solved, not through the field
        const int count = elements.corner_count(e);
        const ElementMeans means = element_means(elements, e);
        for (int k = 0; k < count; ++k) error[e] += means.corner[k] * field[4 * e + std::size_t(k)];
        if (has_bubbles(field, elements)) error[e] += means.bubble * field[bubble_slot(elements, e)];
        error[e] -= radiance[e];
    }
    return error;
}

GatherStatistics gather_statistics(const Elements& elements, const int32_t* material, float hard_edge_angle,
                                   const std::vector<uint8_t>& known, const std::vector<int32_t>& slot_point,
                                   const std::vector<PointStatistics>& point, const CornerColors& solution_light,
                                   const std::vector<Rgb>& field_error, const std::vector<Rgb>& radiance,
                                   const std::vector<Rgb>& emitted) {
    const std::size_t slots = 4 * elements.size();
    std::vector<Rgb> indirect(slots, Rgb(0.0)), variance(slots, Rgb(0.0)), field_noise(slots, Rgb(0.0));
    for (std::size_t e = 0; e < elements.size(); ++e)
        for (int k = 0; k < elements.corner_count(e); ++k) {
            const std::size_t s = 4 * e + std::size_t(k);
            if (!known[s]) continue;
            const Rgb& rho = elements.reflectance[e];
            const PointStatistics& p = point[std::size_t(slot_point[s])];
            indirect[s] = rho * p.indirect;
            variance[s] = rho * rho * p.variance;
            field_noise[s] = rho * rho * p.probe_read * p.probe_read;
        }
    const CornerColors zero{std::vector<Rgb>(solution_light.element_corner.size(), Rgb(0.0)),
                            std::vector<Rgb>(solution_light.input_corner.size(), Rgb(0.0))};
    std::vector<Rgb> reflected(elements.size());
    for (std::size_t e = 0; e < elements.size(); ++e) reflected[e] = radiance[e] - emitted[e];
    GatherStatistics statistics{solution_light, zero, zero, zero, field_error, reflected};
    replace_corners(elements, material, hard_edge_angle, indirect, known, statistics.indirect);
    replace_corners(elements, material, hard_edge_angle, variance, known, statistics.variance);
    replace_corners(elements, material, hard_edge_angle, field_noise, known, statistics.field_noise);
    return statistics;
}

}  // namespace radiosity::detail
