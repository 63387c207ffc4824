/// @file lights.cpp
/// @brief The lamps' direct light onto elements (lights.h): point and spot lamps by their exact
/// unshadowed power on each element and shadow rays from a few of its points, suns by a parallel
/// projection (sun_raster.h).
#include "transport/lights.h"

#include "common/parallel_rows.h"
#include "common/report_progress.h"
#include "common/stratified.h"
#include "transport/cone.h"
#include "transport/lamp_choice.h"
#include "transport/sun_raster.h"
#include "visibility/shadow_ray.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <array>
#include <limits>

namespace radiosity {
namespace {

constexpr int kGrid = 2;  // stratified points per element edge whose shadow rays share its light

/// The light of the point and spot lamps on element `e`, each traced lamp's through `through` (if set).
Rgb element_irradiance(const Elements& elements, std::size_t e, const std::vector<PointLight>& lamps,
                       const hr::Visibility& visibility, const LampLightThrough& through) {
    std::array<Vec3, 4> corners;
    const int count = elements.corner_count(e);
    for (int k = 0; k < count; ++k) corners[k] = elements.vertices[elements.corners[e][k]];
    const Vec3 n = elements.normal[e];
    thread_local std::vector<Rgb> unshadowed;
    unshadowed.resize(lamps.size());
    for (std::size_t l = 0; l < lamps.size(); ++l)
        unshadowed[l] = point_polygon_unshadowed(lamps[l], corners.data(), count, n, elements.area[e]);
    const uint32_t seed = detail::position_seed(elements.centre[e], 0xE1EU);
    std::array<Vec3, kGrid * kGrid> points;
    detail::stratified_points(corners.data(), count, kGrid, seed, points.data());
    return detail::sum_over_lamps(unshadowed, seed, [&](std::size_t l, uint32_t ray_seed, bool fully) {
        const auto trace = [&]() {
            double lit = 0.0, all = 0.0;
            for (const Vec3& x : points) {
                const PointLight& lamp = lamps[l];
                all += max_channel(point_unshadowed(lamp, x, n));
                lit += max_channel(point_irradiance(lamp, visibility, x, n, fully ? point_rays(lamp, x) : 1, ray_seed));
                ray_seed = detail::mix_seed(ray_seed, 1U);
            }
            return all > 0.0 ? unshadowed[l] * (lit / all) : Rgb(0.0);
        };
        return through ? through(e, l, fully, trace) : trace();
    });
}

}  // namespace

namespace {

/// The suns' light, added to `irradiance` (sun_raster.h).
void add_suns(const Elements& elements, const Lights& lights, std::vector<Rgb>& irradiance,
              const ProgressFn& progress) {
    std::size_t done = 0;
    for (const SunLight& sun : lights.suns) {
        add_sun_light(elements, sun, lights.resolution, irradiance);
        detail::report_progress(progress, "lights", ++done, lights.suns.size());
    }
}

/// direct_irradiance over the occluders `visibility`, each traced lamp's light through `through`.
std::vector<Rgb> lit_elements(const Elements& elements, const Lights& lights, const hr::Visibility& visibility,
                              const LampLightThrough& through, const ProgressFn& progress) {
    std::vector<Rgb> irradiance(elements.size(), Rgb(0.0));
    if (elements.size() == 0) return irradiance;
    if (!lights.points.empty())
        detail::parallel_rows("lights", elements.size(), 16, elements.size(), progress, [&](std::size_t e) {
            irradiance[e] = element_irradiance(elements, e, lights.points, visibility, through);
            return true;
        });
    add_suns(elements, lights, irradiance, progress);
    return irradiance;
}

}  // namespace

std::vector<Rgb> direct_irradiance(const Elements& elements, const Lights& lights, const ProgressFn& progress) {
    return direct_irradiance(elements, lights, LampLightThrough(), progress);
}

std::vector<Rgb> direct_irradiance(const Elements& elements, const Lights& lights, const LampLightThrough& through,
                                   const ProgressFn& progress) {
    if (elements.size() == 0 || lights.points.empty()) {
        std::vector<Rgb> irradiance(elements.size(), Rgb(0.0));
        if (elements.size() > 0) add_suns(elements, lights, irradiance, progress);
        return irradiance;
    }
    const hr::Visibility visibility(elements.vertices, detail::blocking_corners(elements),
                                    scene_diagonal(elements.vertices));
    return lit_elements(elements, lights, visibility, through, progress);
}

std::vector<Rgb> direct_irradiance(const Elements& elements, const Lights& lights, const hr::Visibility& visibility,
                                   const ProgressFn& progress) {
    return lit_elements(elements, lights, visibility, LampLightThrough(), progress);
}

}  // namespace radiosity
