/// @file intersection_cut.h
/// @brief Cuts a polygon into convex pieces along the segments where other polygons pass through
/// it, so that no element straddles an intersection; marks the element edges lying on those segments.
#pragma once

#include "geometry/intersection_find.h"
#include "geometry/polygon_geometry.h"

#include <cstdint>
#include <vector>

namespace radiosity::detail {

/// A convex piece of a polygon, CCW like it; corner[k] is the polygon's corner index at points[k],
/// -1 where the cut made the point.
struct Piece {
    std::vector<DVec3> points;
    std::vector<int32_t> corner;
};

/// Splits the polygon (p, unit normal) along the line of each segment in [begin, end), through the
/// pieces that segment crosses (only those: a wall ending mid-floor cuts the floor from its edge to
/// the first piece border beyond the wall's end) and those with one of its ends inside an edge (a
/// block's foot: the cut along one side runs on past the corner, and the piece beyond that line is
/// split where the next side ends on it, so the corner is a vertex of every piece around it).
/// Concave polygons are first cut into triangles.
std::vector<Piece> cut_polygon(const std::vector<DVec3>& p, const DVec3& normal, const CutSegment* begin,
                               const CutSegment* end, double tolerance);

/// Sets the Elements::cut_edges bits of elements [first, size()) for each edge whose two ends lie on
/// a segment's line within `tolerance` and whose middle lies on the segment.
void mark_cut_edges(Elements& elements, std::size_t first, const CutSegment* begin, const CutSegment* end,
                    double tolerance);

}  // namespace radiosity::detail
