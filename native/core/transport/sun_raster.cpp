/// @file sun_raster.cpp
/// @brief Sun lamps: elements projected along the light onto a grid perpendicular to it.
///
/// Each element's lit fraction is the number of cells it wins in the depth test over the number of
/// cells it covers at all; its irradiance is irradiance * cos(theta) times that fraction. Counting
/// both with the same grid cancels the grid's aliasing: an unshadowed element gets the exact value.
/// Elements facing away from the sun only cast shadows. Depth is exact: in a parallel projection
/// it is linear over each triangle.
#include "transport/sun_raster.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace radiosity {
namespace {

struct Projected {
    float x, y, depth;
};

/// Frame (u, v, d) with d the light's direction of travel.
std::array<Vec3, 3> frame_along(const Vec3& d) {
    const Vec3 helper = std::abs(d.z) < 0.9f ? Vec3(0, 0, 1) : Vec3(1, 0, 0);
    const Vec3 u = glm::normalize(glm::cross(helper, d));
    return {u, glm::cross(d, u), d};
}

class Grid {
public:
    Grid(float x0, float y0, float cell, int columns, int rows)
        : x0_(x0),
          y0_(y0),
          cell_(cell),
          columns_(columns),
          rows_(rows),
          depth_(std::size_t(columns) * rows, std::numeric_limits<float>::infinity()),
          item_(std::size_t(columns) * rows, -1) {}

    /// Cells each element covers, whether or not it is nearest there.
    std::vector<uint32_t> covered;

    /// Draws triangle (a, b, c) for element `id` with a depth test (smaller depth = nearer the sun).
    void triangle(Projected a, Projected b, Projected c, int32_t id) {
        float area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
        if (area == 0.0f) return;
        if (area < 0.0f) {
            std::swap(b, c);
            area = -area;
        }
        const int c0 = std::max(0, int(std::floor((std::min({a.x, b.x, c.x}) - x0_) / cell_ - 0.5f)));
        const int c1 = std::min(columns_ - 1, int(std::ceil((std::max({a.x, b.x, c.x}) - x0_) / cell_ - 0.5f)));
        const int r0 = std::max(0, int(std::floor((std::min({a.y, b.y, c.y}) - y0_) / cell_ - 0.5f)));
        const int r1 = std::min(rows_ - 1, int(std::ceil((std::max({a.y, b.y, c.y}) - y0_) / cell_ - 0.5f)));
        for (int r = r0; r <= r1; ++r) {
            const float y = y0_ + (r + 0.5f) * cell_;
            for (int col = c0; col <= c1; ++col) {
                const float x = x0_ + (col + 0.5f) * cell_;
                const float w0 = edge(b, c, x, y), w1 = edge(c, a, x, y), w2 = edge(a, b, x, y);
                if (!(inside(w0, b, c) && inside(w1, c, a) && inside(w2, a, b))) continue;
                ++covered[id];
                const float depth = (w0 * a.depth + w1 * b.depth + w2 * c.depth) / area;
                const std::size_t k = std::size_t(r) * columns_ + col;
                if (depth < depth_[k]) {
                    depth_[k] = depth;
                    item_[k] = id;
                }
            }
        }
    }

    const std::vector<int32_t>& items() const { return item_; }

private:
    static float edge(const Projected& p, const Projected& q, float x, float y) {
        return (q.x - p.x) * (y - p.y) - (q.y - p.y) * (x - p.x);
    }
    /// Counter-clockwise edges; a cell centre exactly on an edge belongs to one side only.
    static bool inside(float w, const Projected& p, const Projected& q) {
        if (w != 0.0f) return w > 0.0f;
        const float dy = q.y - p.y;
        return dy < 0.0f || (dy == 0.0f && q.x < p.x);
    }

    float x0_, y0_, cell_;
    int columns_, rows_;
    std::vector<float> depth_;
    std::vector<int32_t> item_;
};

}  // namespace

void add_sun_light(const Elements& elements, const SunLight& sun, int resolution, std::vector<Rgb>& irradiance) {
    if (elements.size() == 0) return;
    const auto frame = frame_along(glm::normalize(sun.direction));
    std::vector<Projected> p(elements.vertices.size());
    float x_min = INFINITY, x_max = -INFINITY, y_min = INFINITY, y_max = -INFINITY;
    for (std::size_t k = 0; k < p.size(); ++k) {
        const Vec3& v = elements.vertices[k];
        p[k] = {glm::dot(v, frame[0]), glm::dot(v, frame[1]), glm::dot(v, frame[2])};
        x_min = std::min(x_min, p[k].x), x_max = std::max(x_max, p[k].x);
        y_min = std::min(y_min, p[k].y), y_max = std::max(y_max, p[k].y);
    }
    const float cell = std::max(x_max - x_min, y_max - y_min) / resolution;
    if (!(cell > 0.0f)) return;
    const int columns = std::max(1, int(std::ceil((x_max - x_min) / cell))),
              rows = std::max(1, int(std::ceil((y_max - y_min) / cell)));
    Grid grid(x_min, y_min, cell, columns, rows);
    grid.covered.assign(elements.size(), 0);
    for (std::size_t e = 0; e < elements.size(); ++e) {
        // An emitter's two sides cover the same cells at the same depth: the one facing the sun draws.
        if (elements.has_twin(e) && !(-glm::dot(elements.normal[e], frame[2]) > 0.0f)) continue;
        if (!elements.blocks(e)) continue;  // a lamp casts no shadow
        const auto& c = elements.corners[e];
        grid.triangle(p[c[0]], p[c[1]], p[c[2]], int32_t(e));
        if (c[3] >= 0) grid.triangle(p[c[0]], p[c[2]], p[c[3]], int32_t(e));
    }
    std::vector<uint32_t> won(elements.size(), 0);
    for (int32_t id : grid.items())
        if (id >= 0) ++won[id];
    for (std::size_t e = 0; e < elements.size(); ++e) {
        const double cos_theta = -glm::dot(elements.normal[e], frame[2]);
        if (won[e] == 0 || cos_theta <= 0.0) continue;  // shadowed, or the back side: shadow only
        irradiance[e] += sun.irradiance * (cos_theta * won[e] / grid.covered[e]);
    }
}

}  // namespace radiosity
