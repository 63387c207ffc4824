/// @file point_light.h
/// @brief Point and spot lamps, lit as Cycles lights them: a sphere or a disk of the lamp's
/// radius. Their irradiance at a point with soft shadows, the light an element receives with
/// nothing in between, and the rays a point needs. Every consumer (the solve's first shot, the
/// final gather, the hierarchy's lamp detail, the binding) reaches these lamps through here.
#pragma once

#include "common/types.h"
#include "visibility/ray_tracer.h"

#include <cstdint>

namespace radiosity {

/// What a point or spot lamp of radius r > 0 is to the shading point, per Cycles version
/// (intern/cycles/kernel/light/point.h). Each has uniform radiance intensity / (pi r^2), so that
/// far from it the irradiance is intensity cos / d^2.
enum class LampShape : uint8_t {
    Sphere,  ///< Cycles 4.0 and later with Soft Falloff off: a sphere of radius r.
    Disk,    ///< Cycles 3.x, and 4.0 and later with Soft Falloff on (Blender's default): a disk of
             ///< radius r centred on the lamp, facing the shading point.
};

/// A point lamp, or a spot when `cos_half_angle` > -1.
/// `intensity` is radiant intensity in the solver's radiance units: irradiance = I cos / r^2.
struct PointLight {
    Vec3 position{0.0f};
    Rgb intensity{0.0};
    Vec3 direction{0.0f, 0.0f, -1.0f};  ///< spot axis (where it points), unit
    float cos_half_angle = -1.0f;       ///< cos(spot_size / 2); -1 = point lamp
    float smooth = 0.0f;                ///< Cycles' spot_smooth = (1 - cos_half_angle) * spot_blend
    bool cosine_profile = true;         ///< the cone's smoothstep times cos(angle off the axis), as
                                        ///< Cycles 3.x; Cycles 4.0 and later leave the cosine out
    float radius = 0.0f;                ///< Blender's Radius (shadow_soft_size), metres; 0 = a point
    LampShape shape = LampShape::Disk;
};

/// Cycles' spot profile: cos(angle to the axis), faded in by a smoothstep over `smooth`,
/// zero outside the cone; 1 for point lamps.
float spot_profile(const PointLight& light, const Vec3& direction_from_light);

/// The lamp's irradiance at `x` on a surface facing unit `normal` with nothing in between: the
/// clipped cone of the sphere or disk (cone.h), exact for point lamps; spots take their profile
/// along the cone's axis. Cheap: what lamps are chosen by.
Rgb point_unshadowed(const PointLight& light, const Vec3& x, const Vec3& normal);

/// The lamp's light arriving at `x` from every direction with nothing in between, radiance
/// integrated over solid angle: what a medium at `x` takes up per unit of extinction
/// (lamps_in_media.h). I profile / d^2 for a point; a sphere or disk gives its radiance
/// I / (pi r^2) times the solid angle it fills, 2 pi (1 - cos), so a disk gives at most 2 I / r^2
/// (at its centre) and a sphere 4 I / r^2 (inside it). Spots take their profile along the axis.
Rgb point_fluence(const PointLight& light, const Vec3& x);

/// How many shadow rays `x` needs for the lamp's soft shadow: 1 where it looks like a point, up
/// to 64 within about its radius.
int point_rays(const PointLight& light, const Vec3& x);

/// The lamp's irradiance at `x` facing `normal`, shadows included: about `rays` directions
/// stratified over the lamp's cone (uniform in solid angle, jittered from `seed`), each weighted
/// by the lamp's light along it (cosine, spot profile); the exact clipped cone
/// times the weighted share of them that nothing hides. Exact where nothing hides the lamp.
Rgb point_irradiance(const PointLight& light, const hr::Visibility& visibility, const Vec3& x, const Vec3& normal,
                     int rays, uint32_t seed);

/// The lamp's mean irradiance over a planar polygon (3 or 4 `corners`, counter-clockwise about
/// unit `normal`, of `area`) with nothing in between: intensity times the polygon's solid angle
/// seen from the lamp (Van Oosterom and Strackee 1983, "The solid angle of a plane triangle",
/// IEEE TBME 30(2)) over its area, the spot's profile taken at the polygon's centre: the power a
/// point lamp sends the polygon, exactly. A lamp with a radius gives that times the mean ratio of
/// its sphere's or disk's light to the point's over stratified points of the polygon, weighted by
/// the point's light (1 for a sphere above the plane; a disk 8 cm from a surface gives 0.72).
Rgb point_polygon_unshadowed(const PointLight& light, const Vec3* corners, int count, const Vec3& normal, double area);

}  // namespace radiosity
