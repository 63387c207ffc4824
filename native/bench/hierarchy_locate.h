/// @file hierarchy_locate.h
/// @brief Where a point sits in a triangle or a planar quad, in the element's plane: the corner
/// weights that interpolate its colour there.
#pragma once

#include <glm/vec2.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace radiosity::charts {

using Vec2 = glm::dvec2;

inline double cross2(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }

/// Where a point sits in an element: corner weights and how far outside it is (0 = inside).
struct Location {
    double weight[4] = {};
    double outside = std::numeric_limits<double>::infinity();
};

inline Location locate_triangle(const Vec2* c, Vec2 p) {
    Location l;
    const double area = cross2(c[1] - c[0], c[2] - c[0]);
    l.weight[1] = cross2(p - c[0], c[2] - c[0]) / area;
    l.weight[2] = cross2(c[1] - c[0], p - c[0]) / area;
    l.weight[0] = 1.0 - l.weight[1] - l.weight[2];
    l.outside = std::max({0.0, -l.weight[0], -l.weight[1], -l.weight[2]});
    return l;
}

/// Inverse of p = a + u (b - a) + v (d - a) + u v (a - b + c - d).
inline Location locate_quad(const Vec2* c, Vec2 p) {
    const Vec2 e = c[1] - c[0], f = c[3] - c[0], g = c[0] - c[1] + c[2] - c[3], h = p - c[0];
    const double k2 = cross2(g, f), k1 = cross2(e, f) + cross2(h, g), k0 = cross2(h, e);
    auto u_of = [&](double v) {
        const Vec2 d = e + g * v;
        return std::abs(d.x) > std::abs(d.y) ? (h.x - f.x * v) / d.x : (h.y - f.y * v) / d.y;
    };
    Location best;
    auto consider = [&](double v) {
        const double u = u_of(v);
        if (!std::isfinite(u) || !std::isfinite(v)) return;  // a root where the quad's sides are parallel
        const double outside = std::max({0.0, -u, u - 1.0, -v, v - 1.0});
        if (!(outside < best.outside)) return;
        best.outside = outside;
        best.weight[0] = (1 - u) * (1 - v);
        best.weight[1] = u * (1 - v);
        best.weight[2] = u * v;
        best.weight[3] = (1 - u) * v;
    };
    if (std::abs(k2) < 1e-9 * std::abs(k1)) {
        consider(-k0 / k1);
    } else {
        const double w = std::sqrt(std::max(0.0, k1 * k1 - 4.0 * k0 * k2));
        consider((-k1 - w) / (2.0 * k2));
        consider((-k1 + w) / (2.0 * k2));
    }
    return best;
}

}  // namespace radiosity::charts
