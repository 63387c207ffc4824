/// @file open_backs.cpp
/// @brief The faces whose back side looks into the scene (open_backs.h).
#include "visibility/open_backs.h"

#include "common/parallel_rows.h"
#include "common/stratified.h"
#include "visibility/ray_tracer.h"
#include "visibility/shadow_ray.h"

#include <glm/geometric.hpp>

#include <algorithm>

namespace radiosity {
namespace {

constexpr int kElementsPerPolygon = 8;
constexpr int kRaysAlong = 4;             ///< 4 x 4 stratified rays from each element's back
constexpr double kOpenShare = 1.0 / 8.0;  ///< of the rays meeting fronts: the back is open

/// How many of element e's rays from its back meet the front of a surface.
int fronts_behind(const Elements& elements, std::size_t e, const hr::Visibility& rays) {
    const glm::dvec3 n(-elements.normal[e]);
    glm::dvec3 t, b;
    detail::tangent_frame(n, t, b);
    const Vec3 origin = elements.centre[e] - rays.gap() * elements.normal[e];
    int fronts = 0;
    for (int r = 0; r < kRaysAlong * kRaysAlong; ++r) {
        const double u = (double(r % kRaysAlong) + 0.5) / kRaysAlong, v = (double(r / kRaysAlong) + 0.5) / kRaysAlong;
        const Vec3 direction(detail::cosine_direction(n, t, b, u, v));
        const hr::Visibility::Hit hit = rays.first_hit(origin, direction, 0.0f);
        fronts += hit.patch >= 0 && hit.distance > 0.0f &&
                  glm::dot(direction, elements.normal[std::size_t(hit.patch)]) < 0.0f;
    }
    return fronts;
}

}  // namespace

std::vector<uint8_t> open_backs(const Elements& elements, std::size_t polygons) {
    std::vector<uint8_t> open(polygons, 0);
    if (elements.size() == 0) return open;
    std::vector<std::vector<int32_t>> of_polygon(polygons);
    std::vector<uint8_t> skip(polygons, 0);
    for (std::size_t e = 0; e < elements.size(); ++e) {
        const std::size_t p = std::size_t(elements.polygon[e]);
        if (elements.has_twin(e) || !elements.blocks(e) || max_channel(elements.emission[e]) > 0.0)
            skip[p] = 1;
        else if (elements.area[e] > 0.0f)
            of_polygon[p].push_back(int32_t(e));
    }
    const hr::Visibility rays(elements.vertices, detail::blocking_corners(elements), scene_diagonal(elements.vertices));
    detail::parallel_rows("open backs", polygons, 16, 0, {}, [&](std::size_t p) {
        const std::vector<int32_t>& own = of_polygon[p];
        if (skip[p] || own.empty()) return true;
        const std::size_t step = std::max<std::size_t>(1, own.size() / kElementsPerPolygon);
        int fronts = 0, cast = 0;
        for (std::size_t i = 0; i < own.size(); i += step) {
            fronts += fronts_behind(elements, std::size_t(own[i]), rays);
            cast += kRaysAlong * kRaysAlong;
        }
        open[p] = double(fronts) >= kOpenShare * double(cast);
        return true;
    });
    return open;
}

bool any_open(const std::vector<uint8_t>& open) {
    return std::any_of(open.begin(), open.end(), [](uint8_t o) { return o != 0; });
}

}  // namespace radiosity
