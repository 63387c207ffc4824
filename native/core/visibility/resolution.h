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

/// The presets' cells were tuned on the Cornell box seen from half its diagonal (0.866 m), 1.83 times
/// the distance its surfaces see each other at (sight_distance.h: 0.473 m); a little over that, so
/// that the box, and every scene as open as the box, keeps half its diagonal.
constexpr double kSightToResolution = 1.9;

/// The distance resolution_for judges a scene's elements from: kSightToResolution times the
/// distance they see each other at (sight_distance), at most half the diagonal of their bounding
/// box. A game level's rooms are far smaller than its diagonal (q3dm6ish: 5.9 m against 30 m) and
/// no longer pay for its length.
double resolution_distance(double sight_distance, double half_diagonal);

/// resolution_for the scene's small elements (the largest of the smallest elements that hold a
/// tenth of the total area, `area`) seen from `distance` (resolution_distance).
int recommended_resolution(const std::vector<float>& area, double distance, double cells = 8.0);

/// The smallest area that resolution N resolves as recommended_resolution judges it: an element of
/// it, seen head-on from `distance`, covers `cells` cells, A = cells (2 d / N)^2. Smaller emitters
/// are better lit directly (BakeSettings::direct_emitter_area).
double resolved_area(double distance, int resolution, double cells);

}  // namespace radiosity
