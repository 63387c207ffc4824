/// @file lamp_detail.h
/// @brief The lamps' light on the output, exact at its corners (internal). A leaf's radiance is a
/// mean over its area; a lamp's light is known exactly at any point (lamp_points.h). So the output
/// shows the lamps' light as evaluated at its corners plus the rest of the light interpolated,
/// and leaves split after the solve where the lamps' light departs from what their corners show
/// (the edge of a sharp shadow, the bright spot right under a lamp).
#pragma once

#include "hierarchy/tree.h"
#include "visibility/ray_tracer.h"

#include <vector>

namespace radiosity::hr {

/// Splits element leaves, down to children of longest edge `finest`, while the lamps' reflected
/// light (rho E / pi) at a 4 x 4 grid of points inside departs from the interpolation of its
/// values at the leaf's corners by more than `threshold` (radiance). A new leaf takes the light
/// its parent gathered less the parent's lamp light, plus its own (the grid's mean), which is also
/// its entry of `lamp_light` (per node, grown to the new nodes), times its own reflectance. Progress phase "output";
/// throws Cancelled. Returns how many leaves were split.
std::size_t split_for_lamp_light(Tree& tree, const Visibility& visibility, double threshold, float finest,
                                 std::vector<Rgb>& lamp_light, const ProgressFn& progress);

/// The lamps' reflected light (rho E / pi) at each corner of `mesh` (4 slots per element, the 4th
/// of a triangle zero), a hair inside the element: its own side of a shadow edge or contact line
/// through the corner. Progress phase "output"; throws Cancelled.
std::vector<Rgb> lamp_light_at_corners(const Elements& mesh, const Lights& lights, const Visibility& visibility,
                                       const ProgressFn& progress);

}  // namespace radiosity::hr
