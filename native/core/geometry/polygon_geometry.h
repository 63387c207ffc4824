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

/// Whether corner b lies on the straight line from a to c, between them: the turn at b has a sine
/// below `sine`.
bool straight(const DVec3& a, const DVec3& b, const DVec3& c, double sine);

/// Whether every corner turns left about `normal` (strictly: collinear corners are not convex).
bool is_convex(const std::vector<DVec3>& p, const DVec3& normal);

/// Ear clipping in the polygon's plane; handles concave simple polygons. Triangles are CCW about `normal`.
std::vector<std::array<int, 3>> triangulate(const std::vector<DVec3>& p, const DVec3& normal);

/// A simple polygon as convex pieces (Hertel & Mehlhorn 1983): the ear clipping's triangles, joined
/// across each diagonal whose two pieces stay convex together. Each piece lists corner indices of
/// `p`, CCW about `normal`; a convex polygon is one piece.
std::vector<std::vector<int>> convex_pieces(const std::vector<DVec3>& p, const DVec3& normal);

/// How a sliver triangle is cut into strips (scene.cpp). A strip runs from an apex to its short
/// opposite edge, cut across by lines parallel to that edge.
struct SliverSplit {
    bool sliver = false;   ///< longest edge > max_aspect x the height over it
    int apex = 0;          ///< needle: the corner opposite the short edge
    bool at_foot = false;  ///< cap (an angle near 180 degrees): two strips meeting at `foot`
    int longest = 0;       ///< cap: the longest edge runs from corner `longest` to the next
    DVec3 foot{0.0};       ///< cap: the foot of the altitude onto the longest edge
};

/// A needle (one short edge, leaning at most 45 degrees from the altitude) is one strip from the
/// corner opposite it; any other sliver is a cap, split at the altitude's foot into two right
/// triangles, each a strip from an end of the longest edge.
SliverSplit split_sliver(const DVec3& p0, const DVec3& p1, const DVec3& p2, float max_aspect);

/// Clips the segment [a, b], which lies in the convex polygon's plane, to the polygon (Cyrus-Beck);
/// false, a and b untouched, when no more than `tolerance` of it is inside.
bool clip_segment(const std::vector<DVec3>& convex, const DVec3& normal, double tolerance, DVec3& a, DVec3& b);

}  // namespace radiosity::detail
