/// @file open_backs.h
/// @brief The faces whose back side looks into the scene, which reflect from both sides as every
/// face does in Cycles.
///
/// In Cycles a ray that meets a face from behind is shaded with the normal turned towards it, so a
/// face reflects the light that reaches its back (Blender's Diffuse BSDF is two-sided). A face whose
/// back looks into nothing (the outside of a closed room) or into the inside of a closed object
/// gets no light there and needs no back side. One whose back looks at other surfaces' fronts does:
/// a bridge or a table top modelled as one face, a level whose brushes' hidden faces were dropped,
/// a wall of one plane. Such a face gets a back side (SceneInput::open_back, Elements::side) that
/// is solved and lights what it faces. Fronts that are themselves enclosed (all their rays but one
/// meet back faces: the floor under a box without a bottom standing on it) do not count, so the
/// inside of such a box stays one-sided; a floor under a bridge sees out past it and counts.
#pragma once

#include "geometry/scene.h"

#include <cstdint>
#include <vector>

namespace radiosity {

/// Per input polygon (`polygons` of them), 1 where its back looks into the scene: of 16 stratified
/// cosine-weighted rays from the back of each of up to 8 of its elements (`elements`, one-sided,
/// e.g. a first build), at least an eighth meet the front of another surface that is not enclosed
/// (15 of its own 16 rays meet back faces). Emitters' and lamps'
/// polygons are 0 (emitters have their back sides already, lamps block nothing).
std::vector<uint8_t> open_backs(const Elements& elements, std::size_t polygons);

/// Whether `open` (open_backs) gives any polygon a back side.
bool any_open(const std::vector<uint8_t>& open);

}  // namespace radiosity
