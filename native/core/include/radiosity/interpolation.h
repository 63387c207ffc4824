/// @file interpolation.h
/// @brief Element radiances to vertex colours, as the seed interpolates patch radiosities.
///
/// A vertex inside a smooth surface gets the mean of its adjacent elements; a vertex on the
/// surface's border is extrapolated, B(a) = B1 + (B1 - B(e)), with B(e) the mean of the
/// element's interior vertices, and clamped at zero. Elements only share a vertex value when
/// their normals differ by at most the hard-edge angle and their materials are the same.
#pragma once

#include "radiosity/scene.h"

#include <vector>

namespace radiosity {

struct CornerColors {
    /// Per corner of each element (4 per element; the 4th unused for triangles).
    std::vector<Rgb> element_corner;
    /// Per input corner (SceneInput's corner order); zero for skipped polygons.
    std::vector<Rgb> input_corner;
};

/// `material` is SceneInput::material (may be null), `hard_edge_angle` in radians.
CornerColors interpolate_corners(const Elements& elements, const std::vector<Rgb>& radiance,
                                 const int32_t* material, float hard_edge_angle);

}  // namespace radiosity
