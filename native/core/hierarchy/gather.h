/// @file gather.h
/// @brief The light a leaf gathers along its links, evaluated at its output corners instead of
/// spread evenly over it (internal; hierarchy.h).
#pragma once

#include "hierarchy/tree.h"
#include "visibility/ray_tracer.h"

namespace radiosity::hr {

/// A link gives its receiver a mean irradiance: factor x source. How that light varies over the
/// receiver follows from the geometry: an element source's point factor (Lambert's contour
/// integral; cos cos / r^2 from its centre once it is farther than ten of its radii), a cluster's
/// cos / r^2. Each output element's corner takes each of its leaf's and that leaf's ancestors'
/// links as factor x source x (the geometry at the corner / its mean over the receiver's Gauss
/// points, over which the factor was taken), and where the link's rays found the source partly
/// hidden, x (the share rays from the corner see / the link's). So an emitter's light and
/// shadow are right at every corner of a coarse leaf, and a leaf near a bright wall shows the
/// gradient across it.
///
/// For each output element e (whose leaf is `leaf[e]`): `rest[e]` loses rho times the links'
/// mean (what interpolating the leaf's radiance would have shown of them), and
/// `corner_light[4 e + k]` gains rho times their value at corner k (a hair inside the leaf).
/// Left as they were: lamps' links (their light is exact at the corners already,
/// hierarchy/lamp_detail.h), and patches smaller than an element of the minimum size (tessellated
/// objects: their light is below the resolved scale, and they have hundreds of links per leaf).
/// Rays only to sources on such patches are not traced either. Needs the links of the last
/// solve. Progress phase "output"; throws Cancelled.
void gather_at_corners(const Tree& tree, const Visibility& visibility, const Elements& mesh,
                       const std::vector<int32_t>& leaf, std::vector<Rgb>& rest, std::vector<Rgb>& corner_light,
                       const ProgressFn& progress);

/// Whether gather_at_corners reads node `node`'s links: not a cluster's, nor those of patches
/// below the resolved scale. At 10^6 triangles those are most of the bake's memory (the room's
/// walls keep theirs), freed before the output stage.
bool links_gathered(const Tree& tree, int32_t node);

}  // namespace radiosity::hr
