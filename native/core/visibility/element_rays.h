/// @file element_rays.h
/// @brief Stratified cosine-weighted rays from an element, and a polygon's elements sampled evenly:
/// what the passes that judge a polygon by what its elements see share (sizes_by_sight.h,
/// open_backs.h; internal).
#pragma once

#include "common/stratified.h"
#include "geometry/scene.h"
#include "visibility/ray_tracer.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace radiosity::detail {

constexpr int kElementRaysAlong = 4;  ///< 4 x 4 rays from an element
constexpr int kElementRays = kElementRaysAlong * kElementRaysAlong;

/// kElementRays stratified cosine-weighted rays from the centre of element e, on the side `side`
/// faces (its normal, or the negated normal for its back), leaving rays.gap() above it: `seen(direction,
/// hit)` for each that meets a patch beyond 0.
template <typename Seen>
void element_rays(const Elements& elements, std::size_t e, const Vec3& side, const hr::Visibility& rays, Seen seen) {
    const glm::dvec3 n(side);
    glm::dvec3 t, b;
    tangent_frame(n, t, b);
    const Vec3 origin = elements.centre[e] + rays.gap() * side;
    for (int r = 0; r < kElementRays; ++r) {
        const double u = (double(r % kElementRaysAlong) + 0.5) / kElementRaysAlong;
        const double v = (double(r / kElementRaysAlong) + 0.5) / kElementRaysAlong;
        const Vec3 direction(cosine_direction(n, t, b, u, v));
        const hr::Visibility::Hit hit = rays.first_hit(origin, direction, 0.0f);
        if (hit.patch >= 0 && hit.distance > 0.0f) seen(direction, hit);
    }
}

/// `visit(e)` for up to `most` of a polygon's elements `polygon`, every (size / most)-th of them.
template <typename Visit>
void spread_elements(const std::vector<int32_t>& polygon, std::size_t most, Visit visit) {
    const std::size_t step = std::max<std::size_t>(1, polygon.size() / most);
    for (std::size_t i = 0; i < polygon.size(); i += step) visit(std::size_t(polygon[i]));
}

}  // namespace radiosity::detail
