/// @file polygon_geometry.h
/// @brief Planar polygon helpers in double: area vector, convexity, ear clipping, segment clipping.
#pragma once

#include <glm/vec3.hpp>

#include <array>
#include <vector>

namespace radiosity::detail {

using DVec3 = glm::dvec3;

/// Twice the area vector of a polygon (Newell's method): its direction is the normal.
DVec3 newell(const std::vector<DVec3>& p);

/// Whether every corner turns left about `normal` (strictly: collinear corners are not convex).
bool is_convex(const std::vector<DVec3>& p, const DVec3& normal);

/// Ear clipping in the polygon's plane; handles concave simple polygons. Triangles are CCW about `normal`.
std::vector<std::array<int, 3>> triangulate(const std::vector<DVec3>& p, const DVec3& normal);

/// Clips the segment [a, b], which lies in the convex polygon's plane, to the polygon (Cyrus-Beck);
/// false, a and b untouched, when no more than `tolerance` of it is inside.
bool clip_segment(const std::vector<DVec3>& convex, const DVec3& normal, double tolerance, DVec3& a, DVec3& b);

}  // namespace radiosity::detail
