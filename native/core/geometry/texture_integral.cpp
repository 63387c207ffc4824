/// @file texture_integral.cpp
/// @brief Exact texture means over UV polygons (texture_integral.h).
#include "geometry/texture_integral.h"

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace radiosity::detail {
namespace {

using P2 = glm::dvec2;

/// Keeps the part of `polygon` where coordinate `axis` is >= `at` (sign 1) or <= `at` (sign -1)
/// (Sutherland-Hodgman against one line; a concave polygon's result may hold zero-width parts,
/// which add nothing to its area moments).
void clip(std::vector<P2>& polygon, int axis, double at, double sign, std::vector<P2>& scratch) {
    scratch.clear();
    const std::size_t n = polygon.size();
    for (std::size_t k = 0; k < n; ++k) {
        const P2& a = polygon[k];
        const P2& b = polygon[(k + 1) % n];
        const double da = sign * (a[axis] - at), db = sign * (b[axis] - at);
        if (da >= 0.0) scratch.push_back(a);
        if ((da >= 0.0) != (db >= 0.0)) {
            const double t = da / (da - db);
            P2 q = a + t * (b - a);
            q[axis] = at;
            scratch.push_back(q);
        }
    }
    polygon.swap(scratch);
}

/// The signed integrals of 1, x, y and x y over a polygon (Green's theorem), about `origin`.
struct Moments {
    double area = 0, x = 0, y = 0, xy = 0;
};

Moments moments(const std::vector<P2>& polygon, const P2& origin) {
    Moments m;
    const std::size_t n = polygon.size();
    for (std::size_t k = 0; k < n; ++k) {
        const P2 a = polygon[k] - origin, b = polygon[(k + 1) % n] - origin;
        const double cross = a.x * b.y - b.x * a.y;
        m.area += cross;
        m.x += (a.x + b.x) * cross;
        m.y += (a.y + b.y) * cross;
        m.xy += (a.x * b.y + 2.0 * a.x * a.y + 2.0 * b.x * b.y + b.x * a.y) * cross;
    }
    m.area /= 2.0;
    m.x /= 6.0;
    m.y /= 6.0;
    m.xy /= 24.0;
    return m;
}

/// Whether whole cells can be tested against `polygon` (convex, as an element's footprint is):
/// its edges as half-planes a x + b y <= c that hold inside, either winding.
struct HalfPlanes {
    std::vector<glm::dvec3> planes;
    bool convex = true;

    explicit HalfPlanes(const std::vector<P2>& polygon) {
        const std::size_t n = polygon.size();
        double sign = 0.0;
        for (std::size_t k = 0; k < n && convex; ++k) {
            const P2 a = polygon[k], b = polygon[(k + 1) % n], c = polygon[(k + 2) % n];
            const double turn = (b.x - a.x) * (c.y - b.y) - (b.y - a.y) * (c.x - b.x);
            if (turn != 0.0 && sign != 0.0 && (turn > 0.0) != (sign > 0.0)) convex = false;
            if (turn != 0.0) sign = turn;
        }
        if (!convex) return;
        for (std::size_t k = 0; k < n; ++k) {  // left of each edge for counter-clockwise, right for clockwise
            const P2 a = polygon[k], b = polygon[(k + 1) % n];
            const glm::dvec3 plane(sign * (b.y - a.y), -sign * (b.x - a.x), 0.0);
            planes.emplace_back(plane.x, plane.y, plane.x * a.x + plane.y * a.y);
        }
    }

    /// Whether the unit cell at (i, j) lies wholly inside.
    bool holds_cell(double i, double j) const {
        if (!convex) return false;
        for (const glm::dvec3& h : planes)
            for (const P2 corner : {P2(i, j), P2(i + 1, j), P2(i, j + 1), P2(i + 1, j + 1)})
                if (h.x * corner.x + h.y * corner.y > h.z) return false;
        return true;
    }
};

}  // namespace

Rgb footprint_mean(const Texture& t, const std::vector<glm::dvec2>& uv) {
    if (uv.empty()) return Rgb(0.0);
    // In texel units; Linear's patches run between texel centres, half a texel further on.
    const bool linear = t.filter == TextureFilter::Linear;
    const double shift = linear ? 0.5 : 0.0;
    std::vector<P2> polygon;
    P2 low(std::numeric_limits<double>::infinity()), high(-std::numeric_limits<double>::infinity());
    for (const P2& q : uv) {
        polygon.emplace_back(q.x * t.width - shift, q.y * t.height - shift);
        low = glm::min(low, polygon.back());
        high = glm::max(high, polygon.back());
    }
    const double total = moments(polygon, P2(0.0)).area;
    if (!(std::abs(total) > 1e-12) || !std::isfinite(total)) return texel(t, float(uv[0].x), float(uv[0].y));
    const HalfPlanes inside(polygon);
    // A whole cell's moments about its corner, with the polygon's orientation.
    const double orientation = total > 0.0 ? 1.0 : -1.0;
    const Moments whole{orientation, orientation / 2.0, orientation / 2.0, orientation / 4.0};
    Rgb sum(0.0);
    std::vector<P2> cell, scratch;
    for (auto j = int64_t(std::floor(low.y)); double(j) < high.y; ++j)
        for (auto i = int64_t(std::floor(low.x)); double(i) < high.x; ++i) {
            Moments m = whole;
            if (!inside.holds_cell(double(i), double(j))) {
                cell = polygon;
                clip(cell, 0, double(i), 1.0, scratch);
                clip(cell, 0, double(i + 1), -1.0, scratch);
                clip(cell, 1, double(j), 1.0, scratch);
                clip(cell, 1, double(j + 1), -1.0, scratch);
                if (cell.size() < 3) continue;
                m = moments(cell, P2(double(i), double(j)));
            }
            if (!linear) {
                sum += texel_at(t, i, j) * m.area;
                continue;
            }
            // The bilinear patch c00 + (c10 - c00) s + (c01 - c00) t + (c00 - c10 - c01 + c11) s t.
            const Rgb c00 = texel_at(t, i, j), c10 = texel_at(t, i + 1, j);
            const Rgb c01 = texel_at(t, i, j + 1), c11 = texel_at(t, i + 1, j + 1);
            sum += c00 * m.area + (c10 - c00) * m.x + (c01 - c00) * m.y + (c00 - c10 - c01 + c11) * m.xy;
        }
    return sum / total;
}

}  // namespace radiosity::detail
