/// @file sun_light.cpp
/// @brief Sun lamps with an angle (sun_light.h): directions uniform over the cone, the exact
/// clipped cone times the cosine-weighted share of them that nothing hides (as point_light.cpp).
#include "transport/sun_light.h"

#include "transport/cone.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace radiosity {

Rgb sun_unshadowed(const SunLight& sun, const Vec3& normal) {
    const double cosine = -glm::dot(glm::dvec3(normal), glm::dvec3(sun.direction));
    return cosine > 0.0 ? sun.irradiance * cosine : Rgb(0.0);
}

int sun_rays(const SunLight& sun) { return sun.half_angle > 0.0f ? 16 : 1; }

namespace {

/// Cycles 3.x's mean cosine on a surface facing the sun over the uniform cone's, (1 + cos a) / 2:
/// over the disk of radius R = tan a, 2 (sqrt(1 + R^2) - 1) / R^2. Taken as the same where the
/// horizon clips the cone.
double spread_factor(const SunLight& sun, double cos_max) {
    if (!sun.disk_directions) return 1.0;
    const double R2 = (1.0 - cos_max * cos_max) / (cos_max * cos_max);
    return 2.0 * (std::sqrt(1.0 + R2) - 1.0) / R2 / ((1.0 + cos_max) / 2.0);
}

}  // namespace

Rgb sun_irradiance(const SunLight& sun, const hr::Visibility& visibility, const Vec3& x, const Vec3& normal, int rays,
                   uint32_t seed) {
    const glm::dvec3 towards = -glm::dvec3(sun.direction), n(normal);
    if (!(sun.half_angle > 0.0f)) {
        const double cosine = glm::dot(n, towards);
        return cosine > 0.0 && visibility.escapes_from_surface(x, normal, Vec3(towards)) ? sun.irradiance * cosine
                                                                                         : Rgb(0.0);
    }
    const double cos_max = std::cos(double(sun.half_angle)), sin2 = 1.0 - cos_max * cos_max;
    // The mean over the uniform cone of the clipped cosine, exactly.
    const double clipped = detail::clipped_cone_cosine(glm::dot(n, towards), sin2) / (2.0 * M_PI * (1.0 - cos_max));
    if (!(clipped > 0.0)) return Rgb(0.0);
    const detail::Cone cone(towards, cos_max);
    const int grid = std::max(1, int(std::lround(std::sqrt(double(rays)))));
    const double share = detail::lit_share(
        cone, n, grid, seed, [](const glm::dvec3&) { return 1.0; },
        [&](const glm::dvec3& u) { return visibility.escapes_from_surface(x, normal, Vec3(u)); });
    return share > 0.0 ? sun.irradiance * (clipped * spread_factor(sun, cos_max) * share) : Rgb(0.0);
}

}  // namespace radiosity
