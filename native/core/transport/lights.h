/// @file lights.h
/// @brief The lamps of a scene (point, spot, sun) and their direct light onto elements: the
/// solve's first shot, with shadows.
///
/// Lamps have no area in the radiosity system, so they are shot once: each element receives the
/// irradiance E_j of every lamp (occluders included) and reflects rho_j E_j / pi, which the
/// solver then treats as emitted radiance. Area lamps are not here: they are emitting polygons.
/// Each kind of lamp has one home (point_light.h, sun_light.h); docs/lights.md says how to add one.
#pragma once

#include "geometry/scene.h"
#include "transport/point_light.h"
#include "transport/sun_light.h"

#include <functional>
#include <vector>

namespace radiosity {

struct Lights {
    std::vector<PointLight> points;
    std::vector<SunLight> suns;
    int resolution = 1024;  ///< cells per edge of the sun's grid (sun_raster.h)

    bool empty() const { return points.empty() && suns.empty(); }
};

/// Irradiance per element (front side only; elements seen from the back cast shadows). Point and
/// spot lamps: each lamp's unshadowed mean over the element (point_polygon_unshadowed: exact for
/// a point, its sphere or disk near the element by stratified points) times the share of its light that reaches 4
/// stratified points of the element, for the lamps that matter there and a few picked from the rest (lamp_choice.h);
/// suns by sun_raster.h. The cost follows the elements and the lamps that light them. Progress phase "lights", one unit
/// per element and per sun; throws Cancelled.
std::vector<Rgb> direct_irradiance(const Elements& elements, const Lights& lights, const ProgressFn& progress = {});

/// The same with the elements' occluders given (a hr::Visibility of `elements` as direct_irradiance
/// makes it: detail::blocking_corners, scene_diagonal), for a caller that lights them lamp by lamp.
std::vector<Rgb> direct_irradiance(const Elements& elements, const Lights& lights, const hr::Visibility& visibility,
                                   const ProgressFn& progress = {});

/// One traced point or spot lamp's light on element `e` (`l` indexes Lights::points; `fully`: with
/// all the rays its soft shadow needs): `trace()`, or what an earlier bake kept of the same call.
using LampLightThrough =
    std::function<Rgb(std::size_t e, std::size_t l, bool fully, const std::function<Rgb()>& trace)>;

/// direct_irradiance with each traced lamp's light on each element passed through `through` (a
/// re-bake traces only the lamps that changed; bake/kept_first_shot.h).
std::vector<Rgb> direct_irradiance(const Elements& elements, const Lights& lights, const LampLightThrough& through,
                                   const ProgressFn& progress = {});

/// Irradiance at points on surfaces (each facing its unit normal) from every lamp, shadows
/// against `surfaces` (both sides occlude) included, as detail::lamp_irradiance gives it. What the
/// hierarchical bake shows at its output corners; the accuracy charts' truth.
std::vector<Rgb> lamp_irradiance_at(const Elements& surfaces, const Lights& lights, const std::vector<Vec3>& points,
                                    const std::vector<Vec3>& normals);

}  // namespace radiosity
