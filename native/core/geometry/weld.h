/// @file weld.h
/// @brief Welds coincident points (element vertices of neighbouring polygons) into shared ids.
#pragma once

#include "common/types.h"

#include <cstdint>
#include <vector>

namespace radiosity::detail {

/// Gives every point the id of an earlier point within `tolerance` of it (max norm: the first
/// point of its own cell, else of a neighbouring cell), or a new id. Points are bucketed in
/// cells of size `tolerance`; the 27 cells around a point hold every candidate, so whether a
/// point is welded does not depend on where cell borders fall.
/// Returns the ids; `count` receives the number of distinct ids.
std::vector<int32_t> weld_points(const std::vector<Vec3>& points, float tolerance, std::size_t& count);

/// A weld tolerance relative to the scene: 1e-5 of the bounding box diagonal, at least float round-off.
float weld_tolerance(const std::vector<Vec3>& points);

}  // namespace radiosity::detail
