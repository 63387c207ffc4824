/// @file corner_approach.h
/// @brief The direction from which a polygon corner's colour is taken (internal; the final gather).
///
/// Where the light is discontinuous at a vertex (a block's corner on a floor: its edge's shadow
/// and the faces it hides start there), a corner's colour depends on the side it is approached
/// from. Cycles bakes a corner at a point a hair from the vertex towards the centroid of the
/// corner's first loop triangle (Blender's triangulation: a quad's (0 1 2) and (0 2 3)); the
/// gather approaches each corner the same way, along the fan (0 k-1 k) for other polygons.
#pragma once

#include "geometry/scene.h"

#include <vector>

namespace radiosity::detail {

/// Per element vertex: the unit direction in its polygon towards that centroid for the vertices
/// holding an input corner, zero for the others.
std::vector<Vec3> corner_approach(const Elements& elements, const int32_t* face_offsets, std::size_t face_count);

/// How far from its vertex Cycles bakes a corner (bake_offset_towards_center in Cycles' kernel):
/// 1e-4 of the vertex's largest coordinate, at least 1e-4 (float precision at metre scale). Below
/// metre scale the floor follows the scene (`scene_size`), so that a scene scaled by 10^-6 bakes as
/// it does at full size.
float bake_offset(const Vec3& corner, float scene_size);

}  // namespace radiosity::detail
