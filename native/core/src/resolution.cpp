/// @file resolution.cpp
/// @brief Hemi-cube resolution from element areas and the scene's size.
#include "radiosity/resolution.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace radiosity {

int resolution_for(double area, double distance, double cells) {
    if (!(area > 0.0) || !(distance > 0.0) || !(cells > 0.0)) return 32;
    const double n = std::min(1024.0, std::max(32.0, 2.0 * distance * std::sqrt(cells / area)));
    return 2 * static_cast<int>(std::ceil(n / 2.0));
}

namespace {

double half_diagonal(const Elements& elements) {
    Vec3 lo(INFINITY), hi(-INFINITY);
    for (const Vec3& v : elements.vertices) {
        lo = glm::min(lo, v);
        hi = glm::max(hi, v);
    }
    return elements.vertices.empty() ? 0.0 : 0.5 * glm::length(hi - lo);
}

}  // namespace

int recommended_resolution(const Elements& elements, double cells) {
    if (elements.size() == 0) return 32;
    std::vector<float> area = elements.area;
    // The 10th percentile, not the minimum: one stray sliver should not set the cost of the bake.
    auto small = area.begin() + static_cast<std::ptrdiff_t>(area.size() / 10);
    std::nth_element(area.begin(), small, area.end());
    return resolution_for(*small, half_diagonal(elements), cells);
}

double resolved_area(const Elements& elements, int resolution, double cells) {
    if (resolution <= 0) return 0.0;
    const double cell_width = 2.0 * half_diagonal(elements) / resolution;
    return cells * cell_width * cell_width;
}

}  // namespace radiosity
