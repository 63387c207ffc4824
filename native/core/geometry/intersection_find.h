/// @file intersection_find.h
/// @brief Where polygons pass through each other: the segments along which each polygon must be cut.
#pragma once

#include "geometry/scene.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace radiosity::detail {

/// A segment in polygon `polygon`'s plane, inside it, where polygon `by` passes through it.
struct CutSegment {
    int32_t polygon;
    int32_t by;
    glm::dvec3 a, b;
};

/// Distance below which points count as on a polygon's plane: 1e-5 of its longest edge, and never
/// below float round-off at its coordinates (the input is float).
double plane_tolerance(const std::vector<glm::dvec3>& corners);

/// Every segment where a usable polygon has corners strictly on both sides of another usable
/// polygon's plane and the other way round, and the two overlap along their planes' common line;
/// and with `contacts`, every contact line: where a polygon with corners on both sides of another's plane has that
/// other standing on it, an edge in its plane within 1e-5 of the scene's diagonal (a box's side
/// faces on a floor cut the floor along the box's outline); and with `contacts`, the outline of
/// each emitting polygon hung close in front of a parallel polygon, its back side towards it,
/// projected onto it (a light panel under a ceiling: its back side lights the ceiling up to that
/// outline). Polygons meeting at their edges (walls at a corner) and coplanar faces give none.
/// Candidates come from a BoxTree over the polygons' bounding boxes. Sorted by polygon; the
/// segments of one polygon come in a fixed order. `usable[f]` marks polygons with valid corners.
std::vector<CutSegment> find_intersections(const SceneInput& input, const std::vector<char>& usable, bool contacts);

}  // namespace radiosity::detail
