/// @file small_emitters.cpp
/// @brief Small emitters' direct light on every element (small_emitters.h).
#include "transport/small_emitters.h"

#include "common/parallel_rows.h"
#include "common/stratified.h"
#include "transport/near_field.h"
#include "visibility/ray_tracer.h"
#include "visibility/shadow_ray.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace radiosity::detail {
namespace {

std::array<Vec3, 4> corners_of(const Elements& elements, std::size_t e) {
    std::array<Vec3, 4> c{};
    for (int k = 0; k < elements.corner_count(e); ++k) c[k] = elements.vertices[elements.corners[e][k]];
    return c;
}

}  // namespace

std::vector<Rgb> small_emitter_light(const Elements& elements, const std::vector<int32_t>& emitters,
                                     const std::vector<Rgb>& emitted, const ProgressFn& progress) {
    std::vector<Rgb> incoming(elements.size(), Rgb(0.0));
    if (emitters.empty() || elements.size() == 0) return incoming;
    const float scene_size = scene_diagonal(elements.vertices);
    const float lift = 1e-5f * scene_size;  // rays leave and reach a hair off both surfaces
    const hr::Visibility visibility(elements.vertices, blocking_corners(elements), scene_size);
    std::vector<float> radius(elements.size());
    for (std::size_t e = 0; e < elements.size(); ++e) radius[e] = float(circumradius(elements, int32_t(e)));

    parallel_rows("small emitters", elements.size(), 16, elements.size(), progress, [&](std::size_t i) {
        const Vec3 ci = elements.centre[i], ni = elements.normal[i];
        const std::array<Vec3, 4> receiver = corners_of(elements, i);
        std::array<Vec3, 16> from, to;
        Rgb sum(0.0);
        for (const int32_t j : emitters) {
            const std::size_t s = std::size_t(j);
            if (s == i) continue;
            const Vec3 cj = elements.centre[s], nj = elements.normal[s];
            // Wholly behind the emitter, or the emitter wholly behind the receiver: no light.
            if (glm::dot(nj, ci - cj) <= -radius[i] || glm::dot(ni, cj - ci) <= -radius[s]) continue;
            const float distance = glm::length(ci - cj);
            const float reach = radius[i] + radius[s];
            // Gauss points on the smaller element: one far away, up to 4 x 4 close by.
            const int sub = distance > 4.0f * reach ? 1 : distance > 1.5f * reach ? 2 : 4;
            const double flux = area_flux(elements, int32_t(i), j, sub);
            if (!(flux > 0.0)) continue;
            // Visibility from pairs of stratified points, more of them the closer the two are.
            const int grid = distance > 4.0f * reach ? 1 : distance > 1.5f * reach ? 2 : 4;
            const uint32_t seed = mix_seed(uint32_t(i), uint32_t(j));
            const std::array<Vec3, 4> source = corners_of(elements, s);
            stratified_points(source.data(), elements.corner_count(s), grid, seed, from.data());
            stratified_points(receiver.data(), elements.corner_count(i), grid, mix_seed(seed, 1U), to.data());
            double visible = 0.0, total = 0.0;
            for (int k = 0; k < grid * grid; ++k) {
                // Receiver points paired with emitter points in another order, so that rows and
                // columns of the two grids are not always matched.
                const Vec3 a = from[(k * 7 + 3) % (grid * grid)] + lift * nj, b = to[k] + lift * ni;
                const Vec3 d = b - a;
                const float r2 = glm::dot(d, d);
                if (!(r2 > 0.0f)) continue;
                const double kernel =
                    double(std::max(0.0f, glm::dot(nj, d)) * std::max(0.0f, -glm::dot(ni, d))) / (double(r2) * r2);
                if (!(kernel > 0.0)) continue;
                total += kernel;
                if (unhidden(visibility, elements, a, b, ni, scene_size)) visible += kernel;
            }
            // Every ray pair behind one of the planes (a grazing pair): judge by the centres.
            const double share =
                total > 0.0 ? visible / total
                            : double(unhidden(visibility, elements, cj + lift * nj, ci + lift * ni, ni, scene_size));
            sum += emitted[s] * (share * flux / double(elements.area[i]));
        }
        incoming[i] = sum;
        return true;
    });
    return incoming;
}

}  // namespace radiosity::detail
