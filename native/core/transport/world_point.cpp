/// @file world_point.cpp
/// @brief The world's irradiance at an output point, by stratified sampling whose rays go where
/// the sky's edge is (world_light.h).
///
/// A point that sees the sky through a window gets its error from the cells of the stratified
/// (u, v) square that the window's edge crosses: a cell wholly inside or outside it is right with
/// one ray. So a pilot of g x g cosine-weighted rays, one a cell, finds the cells whose ray and a
/// neighbour's disagree (one escapes and the other does not, or they see radiance more than 10%
/// apart), and the cosine's rays are then laid out afresh: one in each cell, and m x m in each of
/// those edge cells, m as large as the rays left allow. The pilot only decides where the rays go,
/// never what they count, so the estimate stays unbiased; each ray, of either strategy, counts
/// L cos / D(w) with D the balance heuristic's density of all the point's rays at w (Veach &
/// Guibas 1995), whose cosine part is g^2 m^2 cos / pi in an edge cell and g^2 cos / pi elsewhere.
/// The map's rays are multi-jittered (multi_jittered_samples), so a small sun's rows get their
/// share of them to a ray.
/// On blender_tests/world_scenes.py's room lit through a window, this has the error that plain
/// stratified sampling reaches with several times the rays (docs/accuracy.md).
#include "transport/world_light.h"

#include "common/stratified.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace radiosity::detail {
namespace {

/// The cosine's rays per pilot ray: the pilot takes a third of them, the cells' own one ray each
/// another third, the edge cells the rest. (Through blender_tests/world_scenes.py's window, from
/// the room's floor, ceiling and far wall, 8192 rays: 0.53% RMS with a third, 0.54% with a quarter,
/// 1.3% with an eighth, against 1.28% for plain stratified rays: test_world.cpp.)
constexpr double kRaysPerPilotRay = 3.0;
/// Fewer cosine rays than this are too few for a pilot to find edges with: they are all spread
/// evenly, one a cell.
constexpr int kMinPilotedRays = 1024;
/// At most this many rays a side in one edge cell (a point that sees a few edge cells spends
/// fewer rays).
constexpr int kMaxSplit = 16;
/// Pilot rays that both escape disagree when their radiance differs by more than this share.
constexpr double kRadianceEdge = 0.1;

struct PilotRay {
    bool escaped = false;
    Rgb radiance{0.0};
};

bool disagree(const PilotRay& a, const PilotRay& b) {
    if (a.escaped != b.escaped) return true;
    if (!a.escaped) return false;
    for (int c = 0; c < 3; ++c)
        if (std::abs(a.radiance[c] - b.radiance[c]) > kRadianceEdge * std::max(a.radiance[c], b.radiance[c]))
            return true;
    return false;
}

/// The cell of the g x g square (u along the rows' index i, v, the azimuth, along j) that
/// cosine_direction maps to unit `w` in the frame (t, b, n): u = sin^2 theta, v = phi / 2 pi.
int cell_of(const glm::dvec3& w, const glm::dvec3& t, const glm::dvec3& b, const glm::dvec3& n, int g) {
    const double z = glm::dot(n, w), u = std::max(0.0, 1.0 - z * z);
    double v = std::atan2(glm::dot(b, w), glm::dot(t, w)) / (2.0 * M_PI);
    v -= std::floor(v);
    const int i = std::min(g - 1, int(u * g)), j = std::min(g - 1, int(v * g));
    return j * g + i;
}

}  // namespace

Rgb WorldSampler::irradiance(const hr::Visibility& visibility, const Vec3& origin, const Vec3& normal,
                             uint32_t seed) const {
    Rgb sum(0.0);
    if (empty_) return sum;
    glm::dvec3 t, b;
    const glm::dvec3 n(normal);
    tangent_frame(n, t, b);
    const bool piloted = point_cos_rays_ >= kMinPilotedRays;
    const int g = piloted ? int(std::sqrt(point_cos_rays_ / kRaysPerPilotRay))
                          : std::max(1, int(std::ceil(std::sqrt(double(point_cos_rays_)) - 1e-9)));
    const int cells = g * g;
    auto direction_in = [&](int cell, int split, int sub) {
        const double u = ((cell % g) + ((sub % split) + double(next_jitter(seed))) / split) / g;
        const double v = ((cell / g) + ((sub / split) + double(next_jitter(seed))) / split) / g;
        return cosine_direction(n, t, b, u, v);
    };

    std::vector<PilotRay> pilot(static_cast<std::size_t>(cells));
    for (int cell = 0; cell < cells && piloted; ++cell) {
        const glm::dvec3 w = direction_in(cell, 1, 0);
        PilotRay& ray = pilot[std::size_t(cell)];
        ray.escaped = glm::dot(n, w) > 0.0 && visibility.escapes(origin, Vec3(w));
        if (ray.escaped) ray.radiance = world_.radiance_from(Vec3(w));
    }
    // Edge cells: a neighbour (diagonals too; the azimuth wraps around) disagrees.
    std::vector<int> split(static_cast<std::size_t>(cells), 1);
    int edges = 0;
    for (int cell = 0; cell < cells; ++cell) {
        const int i = cell % g, j = cell / g;
        bool edge = false;
        for (int dj = -1; dj <= 1 && !edge; ++dj)
            for (int di = -1; di <= 1 && !edge; ++di) {
                if (i + di < 0 || i + di >= g) continue;
                const int other = ((j + dj + g) % g) * g + (i + di);
                edge = disagree(pilot[std::size_t(cell)], pilot[std::size_t(other)]);
            }
        if (edge) {
            split[std::size_t(cell)] = 0;  // marked; sized below
            ++edges;
        }
    }
    const int left = std::max(0, point_cos_rays_ - 2 * cells);
    const int m = edges > 0 ? std::clamp(int(std::sqrt(1.0 + double(left) / edges)), 1, kMaxSplit) : 1;
    for (int& s : split)
        if (s == 0) s = m;

    const int map_count = map_grid_ > 0 ? point_map_grid_ * point_map_grid_ : 0;
    for (int cell = 0; cell < cells; ++cell) {
        const int s = split[std::size_t(cell)];
        for (int sub = 0; sub < s * s; ++sub) {
            const glm::dvec3 w = direction_in(cell, s, sub);
            add(visibility, origin, w, glm::dot(n, w), double(cells) * s * s, map_count, sum);
        }
    }
    const std::vector<glm::dvec2> map_uv =
        map_count > 0 ? multi_jittered_samples(point_map_grid_, seed) : std::vector<glm::dvec2>();
    for (const glm::dvec2& uv : map_uv) {
        const glm::dvec3 w = map_direction(uv.x, uv.y);
        const int s = split[std::size_t(cell_of(w, t, b, n, g))];
        add(visibility, origin, w, glm::dot(n, w), double(cells) * s * s, map_count, sum);
    }
    return sum;
}

}  // namespace radiosity::detail
