/// @file lamp_points.h
/// @brief The lamps' irradiance at one point of a surface, soft shadows included (internal).
#pragma once

#include "transport/cone.h"
#include "transport/lamp_choice.h"
#include "transport/lights.h"
#include "visibility/ray_tracer.h"

#include <vector>

namespace radiosity::detail {

/// Irradiance at `x` on a surface facing `normal` (unit) from every point, spot and sun lamp,
/// each as its kind's own file gives it (point_irradiance, sun_irradiance), the lamps chosen by
/// their unshadowed light there (lamp_choice.h) and the rays seeded by the position of `x`.
Rgb lamp_irradiance(const Lights& lights, const hr::Visibility& visibility, const Vec3& x, const Vec3& normal);

/// lamp_irradiance with each traced lamp's light passed through `through(l, fully, trace)`, which
/// returns `trace()` (the lamp's light with shadows) or what an earlier call of it returned for the
/// same lamp, point and `fully` (output/kept_direct_light.h). Lamp `l` counts the points, then the suns.
template <typename Through>
Rgb lamp_irradiance_through(const Lights& lights, const hr::Visibility& visibility, const Vec3& x, const Vec3& normal,
                            const Through& through) {
    thread_local std::vector<Rgb> unshadowed;
    const std::size_t points = lights.points.size();
    unshadowed.resize(points + lights.suns.size());
    for (std::size_t l = 0; l < points; ++l) unshadowed[l] = point_unshadowed(lights.points[l], x, normal);
    for (std::size_t s = 0; s < lights.suns.size(); ++s)
        unshadowed[points + s] = sun_unshadowed(lights.suns[s], normal);
    return sum_over_lamps(unshadowed, position_seed(x, 0x1A3FU), [&](std::size_t l, uint32_t seed, bool fully) {
        return through(l, fully, [&] {
            if (l < points) {
                const PointLight& lamp = lights.points[l];
                return point_irradiance(lamp, visibility, x, normal, fully ? point_rays(lamp, x) : 1, seed);
            }
            const SunLight& sun = lights.suns[l - points];
            return sun_irradiance(sun, visibility, x, normal, fully ? sun_rays(sun) : 1, seed);
        });
    });
}

}  // namespace radiosity::detail
