/// @file lights.h
/// @brief Direct light from point, spot and sun lamps onto elements: the first shot, with shadows.
///
/// Lamps have no area in the radiosity system, so they are shot once: each element receives the
/// irradiance E_j of every lamp (occluders included) and reflects rho_j E_j / pi, which the
/// solver then treats as emitted radiance. Area lamps are not here: they are emitting polygons.
#pragma once

#include "geometry/scene.h"

#include <vector>

namespace radiosity {

/// An isotropic point lamp, or a spot when `cos_half_angle` > -1.
/// `intensity` is radiant intensity in the solver's radiance units: irradiance = I cos / r^2.
struct PointLight {
    Vec3 position{0.0f};
    Rgb intensity{0.0};
    Vec3 direction{0.0f, 0.0f, -1.0f};  ///< spot axis (where it points), unit
    float cos_half_angle = -1.0f;       ///< cos(spot_size / 2); -1 = point lamp
    float smooth = 0.0f;                ///< Cycles' spot_smooth = (1 - cos_half_angle) * spot_blend
    bool cosine_profile = true;         ///< the cone's smoothstep times cos(angle off the axis), as
                                        ///< Cycles 3.x; Cycles 4.0 and later leave the cosine out
};

/// A distant lamp: parallel light travelling along `direction`, `irradiance` on a plane facing it.
struct SunLight {
    Vec3 direction{0.0f, 0.0f, -1.0f};
    Rgb irradiance{0.0};
};

struct Lights {
    std::vector<PointLight> points;
    std::vector<SunLight> suns;
    int resolution = 1024;  ///< cells per cube-face edge (point, spot) and per edge of the sun's grid

    bool empty() const { return points.empty() && suns.empty(); }
};

/// Cycles' spot profile: cos(angle to the axis), faded in by a smoothstep over `smooth`,
/// zero outside the cone; 1 for point lamps.
float spot_profile(const PointLight& light, const Vec3& direction_from_light);

/// Irradiance per element (front side only; elements seen from the back cast shadows).
/// Progress phase "lights", one unit per lamp; throws Cancelled.
std::vector<Rgb> direct_irradiance(const Elements& elements, const Lights& lights, const ProgressFn& progress = {});

/// Irradiance at points on surfaces (each facing its unit normal), exact: I profile cos / r^2 or a
/// sun's irradiance times cos, from every lamp in front of the point that one shadow ray against
/// `surfaces` (both sides occlude) finds unhidden. What the hierarchical bake shows at its output
/// corners; the accuracy charts' truth.
std::vector<Rgb> lamp_irradiance_at(const Elements& surfaces, const Lights& lights, const std::vector<Vec3>& points,
                                    const std::vector<Vec3>& normals);

}  // namespace radiosity
