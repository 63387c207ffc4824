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

namespace {

/// Whether `hit`, at `at`, lies in the plane through `point` facing unit `normal`.
bool in_plane(const Elements& elements, const hr::Visibility::Hit& hit, const Vec3& at, const Vec3& point,
              const Vec3& normal, float tolerance) {
    return std::abs(glm::dot(elements.normal[hit.patch], normal)) > kParallelCosine &&
           std::abs(glm::dot(at - point, normal)) < tolerance;
}

/// unhidden's ray from `from`, starting `start` along it; hits in the plane through `from` facing
/// `from_normal` do not count either when it is given.
bool unhidden_after(const hr::Visibility& visibility, const Elements& elements, const Vec3& from,
                    const Vec3* from_normal, float start, const Vec3& to, const Vec3& to_normal, float scene_size) {
    const Vec3 d = to - from;
    const float length = glm::length(d);
    if (!(length > 0.0f)) return true;
    const Vec3 direction = d / length;
    const float end = length * (1.0f - 1e-4f) - visibility.gap();
    const float tolerance = 1e-5f * scene_size + 1e-4f * length;
    float t = start;
    for (int step = 0; step < 16; ++step) {
        const hr::Visibility::Hit hit = visibility.first_hit(from, direction, t);
        if (hit.patch < 0 || !(hit.distance < end)) return true;
        const Vec3 at = from + hit.distance * direction;
        if (!in_plane(elements, hit, at, to, to_normal, tolerance) &&
            !(from_normal != nullptr && in_plane(elements, hit, at, from, *from_normal, tolerance)))
            return false;
        t = std::nextafter(hit.distance, std::numeric_limits<float>::max());
    }
    return true;
}

}  // namespace

bool unhidden(const hr::Visibility& visibility, const Elements& elements, const Vec3& from, const Vec3& to,
              const Vec3& to_normal, float scene_size) {
    return unhidden_after(visibility, elements, from, nullptr, std::max(visibility.gap(), 1e-6f), to, to_normal,
                          scene_size);
}

bool unhidden_from_surface(const hr::Visibility& visibility, const Elements& elements, const Vec3& origin,
                           const Vec3& normal, const Vec3& to, const Vec3& to_normal, float scene_size) {
    return unhidden_after(visibility, elements, origin, &normal, 0.0f, to, to_normal, scene_size);
}

}  // namespace radiosity::detail
