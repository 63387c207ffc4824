/// @file sun_light.h
/// @brief Sun lamps, lit as Cycles lights them: parallel light from a cone of directions of the
/// lamp's angle. Their irradiance at a point with soft shadows and the light they give elements
/// (sun_raster.h). Every consumer reaches sun lamps through here.
#pragma once

#include "common/types.h"
#include "visibility/ray_tracer.h"

#include <cstdint>

namespace radiosity {

/// A distant lamp: light travelling along `direction` (unit), `irradiance` on a plane facing it,
/// from directions within `half_angle` (Blender's Angle / 2) of it.
struct SunLight {
    Vec3 direction{0.0f, 0.0f, -1.0f};
    Rgb irradiance{0.0};
    float half_angle = 0.0f;
    /// How Cycles spreads the directions (intern/cycles/kernel/light): 3.x over a disk of radius
    /// tan(half_angle) one unit along the direction (distant_light_sample: uniform in that disk's
    /// area, radiance ~ 1 / cos^3), 4.0 and later uniformly over the cone (sample_uniform_cone).
    bool disk_directions = false;
};

/// The sun's irradiance at a surface facing unit `normal` with nothing in between, the cone's
/// spread taken as its axis: irradiance cos theta. Cheap: what lamps are chosen by.
Rgb sun_unshadowed(const SunLight& sun, const Vec3& normal);

/// Shadow rays a point needs for the sun's soft shadow: 1 for a sun without angle, 16 with one.
int sun_rays(const SunLight& sun);

/// The sun's irradiance at `x` facing `normal`, shadows included: irradiance times the exact mean
/// of the clipped cosine over the cone (cone.h), times the share of about `rays` directions
/// stratified over the cone (jittered from `seed`) that nothing hides, each weighted by its cosine;
/// `disk_directions` scales it by Cycles 3.x's mean cosine over the uniform cone's.
Rgb sun_irradiance(const SunLight& sun, const hr::Visibility& visibility, const Vec3& x, const Vec3& normal, int rays,
                   uint32_t seed);

}  // namespace radiosity
