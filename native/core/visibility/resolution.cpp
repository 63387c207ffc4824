/// @file resolution.cpp
/// @brief Hemi-cube resolution from element areas and the distance they are seen from.
#include "visibility/resolution.h"

#include <algorithm>
#include <cmath>

namespace radiosity {

int resolution_for(double area, double distance, double cells) {
    if (!(area > 0.0) || !(distance > 0.0) || !(cells > 0.0)) return 32;
    const double n = std::min(1024.0, std::max(32.0, 2.0 * distance * std::sqrt(cells / area)));
    return 2 * static_cast<int>(std::ceil(n / 2.0));
}

double resolution_distance(double sight_distance, double half_diagonal) {
    return std::min(half_diagonal, kSightToResolution * sight_distance);
}

int recommended_resolution(const std::vector<float>& element_area, double distance, double cells) {
    if (element_area.empty()) return 32;
    // The smallest elements that hold a tenth of the surface, not a tenth by count: a prop made of
    // thousands of tiny faces (a text object, a cut contact line) carries little of the light, and
    // must not set the cost of the whole bake.
    std::vector<float> area = element_area;
    std::sort(area.begin(), area.end());
    double total = 0.0;
    for (const float a : area) total += std::max(0.0f, a);
    double held = 0.0;
    std::size_t k = 0;
    while (k + 1 < area.size() && (held += std::max(0.0f, area[k])) < 0.1 * total) ++k;
    return resolution_for(area[k], distance, cells);
}

double resolved_area(double distance, int resolution, double cells) {
    if (resolution <= 0) return 0.0;
    const double cell_width = 2.0 * distance / resolution;
    return cells * cell_width * cell_width;
}

}  // namespace radiosity
