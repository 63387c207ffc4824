/// @file sizes_by_sight.h
/// @brief The element size each polygon's surroundings ask for: no larger than the distance at which
/// it sees other surfaces.
///
/// The light on a surface changes on the scale of the distance to what lights it. In an open room
/// that is the room's size, and the bake's element size resolves it; in a trench 0.4 m wide, a gap
/// under a cabinet or a narrow duct, the light falls off from the opening within a few widths,
/// and elements as long as the room's (a game level's 3.9 m) spread the lit end's light over the
/// dark one: the far end of a trench under a lamp came out 8 times Cycles' light, at 0.8 m elements
/// 2.7 times. So a polygon whose rays meet other surfaces nearer than the element size is cut to
/// that distance (the harmonic mean of its cosine-weighted rays' hit distances, the distance that
/// weighs near surfaces as their form factors do), and its elements merge only up to it
/// (cluster_elements). Geometry alone decides: a re-bake after a change of light keeps them.
#pragma once

#include "geometry/scene.h"

#include <vector>

namespace radiosity {

/// Per input polygon (`polygons` of them), the longest edge its elements may have where that is
/// less than three quarters of `element_size`, else 0: the harmonic mean of the hit distances of
/// 16 cosine-weighted rays from each of up to 8 of its elements (`elements`, built at
/// `element_size`), at least an eighth of the element size. Polygons whose elements are all shorter
/// than that eighth, emitters' and lamps' are left at 0.
std::vector<float> sizes_by_sight(const Elements& elements, std::size_t polygons, float element_size);

/// Whether `sizes` (sizes_by_sight) asks any polygon for smaller elements.
bool any_size(const std::vector<float>& sizes);

}  // namespace radiosity
