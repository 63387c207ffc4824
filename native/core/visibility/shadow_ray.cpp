/// @file shadow_ray.cpp
/// @brief Shadow rays that ignore the target's own plane (shadow_ray.h).
#include "visibility/shadow_ray.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace radiosity::detail {

std::vector<std::array<int32_t, 4>> blocking_corners(const Elements& elements) {
    std::vector<std::array<int32_t, 4>> corners = elements.corners;
    for (std::size_t e = 0; e < corners.size(); ++e)
        if (!elements.blocks(e)) corners[e] = {corners[e][0], corners[e][0], corners[e][0], -1};
    return corners;
}

bool unhidden(const hr::Visibility& visibility, const Elements& elements, const Vec3& from, const Vec3& to,
              const Vec3& to_normal, float scene_size) {
    const Vec3 d = to - from;
    const float length = glm::length(d);
    if (!(length > 0.0f)) return true;
    const Vec3 direction = d / length;
    const float end = length * (1.0f - 1e-4f) - visibility.gap();
    const float tolerance = 1e-5f * scene_size + 1e-4f * length;
    float t = std::max(visibility.gap(), 1e-6f);
    for (int step = 0; step < 16; ++step) {
        const hr::Visibility::Hit hit = visibility.first_hit(from, direction, t);
        if (hit.patch < 0 || !(hit.distance < end)) return true;
        const Vec3 at = from + hit.distance * direction;
        const bool in_plane = std::abs(glm::dot(elements.normal[hit.patch], to_normal)) > 0.9999f &&
                              std::abs(glm::dot(at - to, to_normal)) < tolerance;
        if (!in_plane) return false;
        t = std::nextafter(hit.distance, std::numeric_limits<float>::max());
    }
    return true;
}

}  // namespace radiosity::detail
