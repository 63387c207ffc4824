/// @file interpolation.h
/// @brief Element radiances to vertex colours, as classic radiosity interpolates patch radiosities to vertices
/// (averaged inside, extrapolated at borders).
///
/// A vertex inside a smooth surface gets the mean of its adjacent elements; a vertex on the
/// surface's border is extrapolated, B(a) = B1 + (B1 - B(e)), with B(e) the mean of the
/// element's interior vertices, and clamped at zero. Elements only share a vertex value when
/// their normals differ by at most the hard-edge angle and their materials are the same.
#pragma once

#include "geometry/scene.h"

#include <vector>

namespace radiosity {

/// `material` is SceneInput::material (may be null), `hard_edge_angle` in radians.
/// `corner_light` (optional, 4 per element): light known at each element corner itself (the
/// lamps', evaluated there), added to the corners interpolated from `radiance` as its mean over
/// the elements that share the corner's colour, so that a smooth surface's shared corners keep
/// one value.
CornerColors interpolate_corners(const Elements& elements, const std::vector<Rgb>& radiance, const int32_t* material,
                                 float hard_edge_angle, const std::vector<Rgb>* corner_light = nullptr);

/// Replaces the colours of the slots (4 per element, as `corner_light`) marked in `known`, and the
/// input corners on them, by `slot_value` (clamped at zero): the final gather's values in place
/// of interpolated ones. Where a slot's compatible set (the elements that share its colour) bends,
/// its value is the mean over the known slots of the set that are not coplanar with it, so a
/// curved smooth surface's corners keep one value; coplanar faces keep their own (on a flat
/// surface the light at a vertex differs between faces only where it is discontinuous, as at a
/// block's corner standing on a floor).
void replace_corners(const Elements& elements, const int32_t* material, float hard_edge_angle,
                     const std::vector<Rgb>& slot_value, const std::vector<uint8_t>& known, CornerColors& colors);

}  // namespace radiosity
