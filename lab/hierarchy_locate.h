/// @file hierarchy_locate.h
/// @brief Where a point sits in a triangle or a planar quad, in the element's plane: the corner
/// weights that interpolate its colour there, as Blender shows it.
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

/// A quad as Blender draws and renders it: two triangles, corners 0 1 2 and 0 2 3 (its
/// tessellation of convex quads), each interpolating its corners linearly. A bilinear patch
/// would measure colours no artist sees.
inline Location locate_quad(const Vec2* c, Vec2 p) {
    const Vec2 first[3] = {c[0], c[1], c[2]}, second[3] = {c[0], c[2], c[3]};
    const Location a = locate_triangle(first, p), b = locate_triangle(second, p);
    if (a.outside <= b.outside) return a;  // weight[3] stays 0
    Location l;
    l.outside = b.outside;
    l.weight[0] = b.weight[0];
    l.weight[2] = b.weight[1];
    l.weight[3] = b.weight[2];
    return l;
}

}  // namespace radiosity::charts
