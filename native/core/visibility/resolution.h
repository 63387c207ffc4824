/// @file resolution.h
/// @brief A hemi-cube resolution from the scene: small or distant elements must cover cells.
///
/// An element of solid angle Omega covers about Omega N^2 / 4 cells of the top face; below a few
/// cells its factor aliases (it falls between cell centres or takes a whole cell). Measured on a
/// small square seen from 1 m at 64 directions (docs/stability.md): relative RMS error of its
/// factor ~ 0.35 cells^-0.7, i.e. 13% at 4 cells, 8% at 8, 3% at 30.
#pragma once

#include <vector>

namespace radiosity {

/// Smallest even resolution N at which an element of `area` seen head-on from `distance` covers
/// `cells` cells: N = 2 d sqrt(cells / A), clamped to [32, 1024].
int resolution_for(double area, double distance, double cells);

/// resolution_for the scene's small elements (the largest of the smallest elements that hold a
/// tenth of the total area, `area`) seen from `distance`, the distance at which the scene's surfaces
/// see each other (sight_distance.h).
int recommended_resolution(const std::vector<float>& area, double distance, double cells = 8.0);

/// The smallest area that resolution N resolves as recommended_resolution judges it: an element of
/// it, seen head-on from `distance`, covers `cells` cells, A = cells (2 d / N)^2. Smaller emitters
/// are better lit directly (BakeSettings::direct_emitter_area).
double resolved_area(double distance, int resolution, double cells);

}  // namespace radiosity
