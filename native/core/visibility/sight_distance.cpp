/// @file sight_distance.cpp
/// @brief Hit distances of cosine-weighted rays from area-stratified points, by Embree.
#include "visibility/sight_distance.h"

#include "visibility/ray_tracer.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace radiosity {

double half_diagonal(const Elements& elements) {
    Vec3 lo(INFINITY), hi(-INFINITY);
    for (const Vec3& v : elements.vertices) {
        lo = glm::min(lo, v);
        hi = glm::max(hi, v);
    }
    return elements.vertices.empty() ? 0.0 : 0.5 * glm::length(hi - lo);
}

namespace {

/// The elements that block rays (every one but lamps').
std::vector<int32_t> blocking(const Elements& elements) {
    std::vector<int32_t> kept;
    for (std::size_t e = 0; e < elements.size(); ++e)
        if (elements.blocks(e) && elements.area[e] > 0.0f) kept.push_back(int32_t(e));
    return kept;
}

/// Element k of `count` points stratified over the cumulative area of `kept`: the one holding the
/// middle of stratum k.
std::vector<int32_t> stratified_by_area(const Elements& elements, const std::vector<int32_t>& kept, int count) {
    std::vector<double> cumulative(kept.size());
    double total = 0.0;
    for (std::size_t k = 0; k < kept.size(); ++k) cumulative[k] = total += elements.area[kept[k]];
    std::vector<int32_t> chosen;
    for (int k = 0; k < count; ++k) {
        const double at = (k + 0.5) / count * total;
        const auto it = std::lower_bound(cumulative.begin(), cumulative.end(), at);
        chosen.push_back(kept[std::min<std::size_t>(it - cumulative.begin(), kept.size() - 1)]);
    }
    return chosen;
}

/// Ray `i`'s cosine-weighted direction about unit `normal`, from the R2 sequence (Roberts 2018):
/// a low-discrepancy set of the unit square, mapped by Malley's method.
Vec3 cosine_direction(const Vec3& normal, std::size_t i) {
    const double u = std::fmod(0.5 + 0.7548776662466927 * double(i), 1.0);
    const double v = std::fmod(0.5 + 0.5698402909980532 * double(i), 1.0);
    const double r = std::sqrt(u), phi = 2.0 * M_PI * v;
    const Vec3 t = glm::normalize(std::abs(normal.x) < 0.9f ? glm::cross(normal, Vec3(1, 0, 0))
                                                            : glm::cross(normal, Vec3(0, 1, 0)));
    const Vec3 b = glm::cross(normal, t);
    const float z = float(std::sqrt(std::max(0.0, 1.0 - u)));
    return glm::normalize(float(r * std::cos(phi)) * t + float(r * std::sin(phi)) * b + z * normal);
}

}  // namespace

double sight_distance(const Elements& elements, const SightSettings& settings) {
    const std::vector<int32_t> kept = blocking(elements);
    if (kept.empty()) return half_diagonal(elements);
    std::vector<std::array<int32_t, 4>> corners;
    for (const int32_t e : kept) corners.push_back(elements.corners[e]);
    const hr::Visibility rays(elements.vertices, corners, float(2.0 * half_diagonal(elements)));
    double sum = 0.0;
    std::size_t hits = 0, i = 0;
    for (const int32_t e : stratified_by_area(elements, kept, settings.points))
        for (int d = 0; d < settings.directions; ++d, ++i) {
            const auto hit = rays.first_hit(elements.centre[e], cosine_direction(elements.normal[e], i), rays.gap());
            const bool near = settings.skip_near_hits && hit.distance < std::sqrt(elements.area[e]);
            if (hit.patch < 0 || near) continue;
            sum += std::pow(double(hit.distance), settings.exponent);
            ++hits;
        }
    return hits == 0 ? half_diagonal(elements) : std::pow(sum / double(hits), 1.0 / settings.exponent);
}

}  // namespace radiosity
