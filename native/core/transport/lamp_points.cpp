/// @file lamp_points.cpp
/// @brief The lamps' irradiance at points, one shadow ray per lamp (lamp_points.h, lights.h).
#include "transport/lamp_points.h"

#include <tbb/parallel_for.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <limits>
#include <stdexcept>

namespace radiosity {
namespace detail {

Rgb lamp_irradiance(const Lights& lights, const hr::Visibility& visibility, const Vec3& x, const Vec3& normal) {
    Rgb irradiance(0.0);
    for (const PointLight& lamp : lights.points) {
        const Vec3 d = lamp.position - x;
        const float distance2 = glm::dot(d, d);
        if (!(distance2 > 0.0f)) continue;
        const Vec3 u = d / std::sqrt(distance2);
        const float cosine = glm::dot(normal, u);
        const float profile = spot_profile(lamp, -u);
        if (cosine > 0.0f && profile > 0.0f && visibility.clear(x, lamp.position))
            irradiance += lamp.intensity * double(cosine * profile / distance2);
    }
    for (const SunLight& sun : lights.suns) {
        const float cosine = -glm::dot(normal, sun.direction);
        if (cosine > 0.0f && visibility.clear_towards(x, -sun.direction)) irradiance += sun.irradiance * double(cosine);
    }
    return irradiance;
}

}  // namespace detail

std::vector<Rgb> lamp_irradiance_at(const Elements& surfaces, const Lights& lights, const std::vector<Vec3>& points,
                                    const std::vector<Vec3>& normals) {
    if (points.size() != normals.size()) throw std::invalid_argument("lamp_irradiance_at: one normal per point");
    Vec3 low(std::numeric_limits<float>::max()), high(-std::numeric_limits<float>::max());
    for (const Vec3& v : surfaces.vertices) {
        low = glm::min(low, v);
        high = glm::max(high, v);
    }
    const float size = surfaces.vertices.empty() ? 1.0f : glm::length(high - low);
    const hr::Visibility visibility(surfaces.vertices, surfaces.corners, size);
    std::vector<Rgb> irradiance(points.size());
    tbb::parallel_for(std::size_t(0), points.size(), [&](std::size_t i) {
        irradiance[i] = detail::lamp_irradiance(lights, visibility, points[i], normals[i]);
    });
    return irradiance;
}

}  // namespace radiosity
