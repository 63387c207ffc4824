/// @file lamp_points.cpp
/// @brief The lamps' irradiance at points (lamp_points.h, lights.h).
#include "transport/lamp_points.h"

#include <tbb/parallel_for.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <limits>
#include <stdexcept>

namespace radiosity {
namespace detail {

Rgb lamp_irradiance(const Lights& lights, const hr::Visibility& visibility, const Vec3& x, const Vec3& normal) {
    return lamp_irradiance_through(lights, visibility, x, normal,
                                   [](std::size_t, bool, const auto& trace) { return trace(); });
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
