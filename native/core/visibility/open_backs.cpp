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
constexpr int kEnclosedBacks = 15;        ///< of an element's 16 rays meeting back faces: it is enclosed

/// kRaysAlong^2 stratified cosine-weighted rays from element e's side facing `n` (its normal or its
/// back's), each passed to `seen(direction, hit)`.
template <typename Seen>
void rays_from(const Elements& elements, std::size_t e, const Vec3& n, const hr::Visibility& rays, Seen seen) {
    const glm::dvec3 axis(n);
    glm::dvec3 t, b;
    detail::tangent_frame(axis, t, b);
    const Vec3 origin = elements.centre[e] + rays.gap() * n;
    for (int r = 0; r < kRaysAlong * kRaysAlong; ++r) {
        const double u = (double(r % kRaysAlong) + 0.5) / kRaysAlong, v = (double(r / kRaysAlong) + 0.5) / kRaysAlong;
        const Vec3 direction(detail::cosine_direction(axis, t, b, u, v));
        const hr::Visibility::Hit hit = rays.first_hit(origin, direction, 0.0f);
        if (hit.patch >= 0 && hit.distance > 0.0f) seen(direction, std::size_t(hit.patch));
    }
}

/// Whether element `hit` shows its front to a ray along `direction`.
bool faces(const Elements& elements, const Vec3& direction, std::size_t hit) {
    return glm::dot(direction, elements.normal[hit]) < 0.0f;
}

/// Per element, whether all its rays but one meet back faces: it lies inside something (the floor
/// under a box standing on it), and no light reaches it. A floor under a bridge sees out past it.
std::vector<uint8_t> enclosed_elements(const Elements& elements, const hr::Visibility& rays) {
    std::vector<uint8_t> enclosed(elements.size(), 0);
    detail::parallel_rows("open backs", elements.size(), 256, 0, {}, [&](std::size_t e) {
        int backs = 0;
        rays_from(elements, e, elements.normal[e], rays,
                  [&](const Vec3& direction, std::size_t hit) { backs += !faces(elements, direction, hit); });
        enclosed[e] = backs >= kEnclosedBacks;
        return true;
    });
    return enclosed;
}

/// How many of element e's rays from its back meet the front of a surface that is not enclosed.
int fronts_behind(const Elements& elements, std::size_t e, const hr::Visibility& rays,
                  const std::vector<uint8_t>& enclosed) {
    int fronts = 0;
    rays_from(elements, e, -elements.normal[e], rays, [&](const Vec3& direction, std::size_t hit) {
        fronts += faces(elements, direction, hit) && !enclosed[hit];
    });
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
    const std::vector<uint8_t> enclosed = enclosed_elements(elements, rays);
    detail::parallel_rows("open backs", polygons, 16, 0, {}, [&](std::size_t p) {
        const std::vector<int32_t>& own = of_polygon[p];
        if (skip[p] || own.empty()) return true;
        const std::size_t step = std::max<std::size_t>(1, own.size() / kElementsPerPolygon);
        int fronts = 0, cast = 0;
        for (std::size_t i = 0; i < own.size(); i += step) {
            fronts += fronts_behind(elements, std::size_t(own[i]), rays, enclosed);
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
