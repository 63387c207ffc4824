/// @file sizes_by_sight.h
/// @brief The element size each polygon's surroundings ask for: no larger than the distance at which
/// it sees other surfaces.
///
/// The light on a surface changes on the scale of the distance to what lights it. In an open room
/// that is the room's size, which the bake's element size resolves; in a trench, a slot or a gap
/// under a cabinet the light falls off from the opening within a few widths, and elements as long
/// as a room's spread the lit end's light over the dark end (a game level's trench: docs/accuracy.md).
/// So a polygon whose elements see other surfaces nearer than a quarter of the element size is cut
/// to that distance, and its elements merge only up to it (cluster_elements). The distance of an
/// element is the harmonic mean of the hit distances of its cosine-weighted rays, which weighs near
/// surfaces as their form factors do (the distance Ward, Rubinstein & Clear 1988's irradiance cache
/// judges how far light may be carried by); a polygon's is the median over a few of its elements, so that
/// a floor narrow only beside a pillar or running on under a wall (its buried elements' rays meet
/// back faces) keeps the element size. Geometry alone decides: a re-bake after a change of light
/// keeps the elements.
#pragma once

#include "geometry/scene.h"

#include <vector>

namespace radiosity {

/// Per input polygon (`polygons` of them), the longest edge its elements may have where that is
/// less than a quarter of `element_size`, else 0: the median over up to 8 of its elements
/// (`elements`, built at `element_size`) of the harmonic mean distance at which 16 stratified
/// cosine-weighted rays from each meet fronts (elements whose rays mostly meet back faces nearer
/// than their size lie under other geometry and do not count), at least an eighth of the element
/// size, and at least what keeps the elements the cuts add within half of `elements`' count (2,048
/// in a small scene). Polygons whose elements are all shorter than that eighth, emitters' and lamps'
/// are left at 0.
std::vector<float> sizes_by_sight(const Elements& elements, std::size_t polygons, float element_size);

/// Whether `sizes` (sizes_by_sight) asks any polygon for smaller elements.
bool any_size(const std::vector<float>& sizes);

}  // namespace radiosity
