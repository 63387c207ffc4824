/// @file lights.cpp
/// @brief Point and spot lamps by a full cube around the lamp; sun lamps by a parallel projection.
///
/// A lamp's cube item buffer tells which element each direction hits first; the flux an element
/// receives is sum over its cells of I(direction) * solid angle, and its irradiance that flux over
/// its area. This conserves the lamp's power exactly and shadows come for free.
#include "transport/lights.h"

#include "common/report_progress.h"
#include "transport/sun_raster.h"
#include "visibility/hemicube.h"

#include <glm/geometric.hpp>

namespace radiosity {

float spot_profile(const PointLight& light, const Vec3& direction_from_light) {
    if (light.cos_half_angle <= -1.0f) return 1.0f;
    const float cos_angle = glm::dot(direction_from_light, light.direction);
    if (cos_angle <= light.cos_half_angle) return 0.0f;
    const float t = cos_angle - light.cos_half_angle;
    const float falloff = light.cosine_profile ? cos_angle : 1.0f;
    if (light.smooth <= 0.0f || t >= light.smooth) return falloff;
    const float s = t / light.smooth;
    return falloff * s * s * (3.0f - 2.0f * s);
}

namespace {

void add_point_light(const Elements& elements, const PointLight& light, Hemicube& cube, std::vector<Rgb>& irradiance) {
    cube.render_sphere(elements, light.position, -1);
    const std::vector<float>& solid_angle = cube.weights().solid_angle;
    std::vector<float> weight(solid_angle);
    if (light.cos_half_angle > -1.0f)
        for (std::size_t cell = 0; cell < weight.size(); ++cell)
            weight[cell] *= spot_profile(light, cube.cell_direction(cell));
    SparseRow flux;
    cube.accumulate(weight, flux);
    for (std::size_t k = 0; k < flux.col.size(); ++k) {
        const int32_t j = flux.col[k];
        irradiance[j] += light.intensity * (double(flux.val[k]) / elements.area[j]);
    }
}

}  // namespace

std::vector<Rgb> direct_irradiance(const Elements& elements, const Lights& lights, const ProgressFn& progress) {
    std::vector<Rgb> irradiance(elements.size(), Rgb(0.0));
    const std::size_t total = lights.points.size() + lights.suns.size();
    std::size_t done = 0;
    if (!lights.points.empty()) {
        Hemicube cube(CubeWeights::make(lights.resolution));
        for (const PointLight& light : lights.points) {
            add_point_light(elements, light, cube, irradiance);
            detail::report_progress(progress, "lights", ++done, total);
        }
    }
    for (const SunLight& sun : lights.suns) {
        add_sun_light(elements, sun, lights.resolution, irradiance);
        detail::report_progress(progress, "lights", ++done, total);
    }
    return irradiance;
}

}  // namespace radiosity
