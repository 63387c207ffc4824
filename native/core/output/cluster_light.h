/// @file cluster_light.h
/// @brief The output elements' light from a solve over merged elements (geometry/clusters.h).
#pragma once

#include "geometry/clusters.h"

#include <vector>

namespace radiosity::detail {

/// The output elements' radiance from the solve elements' `radiance`. An output element that is a
/// solve element keeps its radiance. Within a merged cluster the light is not flat: the solve
/// elements' radiance is interpolated to their corners as the output is (interpolation.h), read at
/// each member's centre (bilinear over a quad, linear over a triangle), then shifted so that the
/// members' mean by area is the cluster's radiance (the light the solve balanced), and clamped at
/// zero. So the members' radiance varies as the solution does across the clusters, and the final
/// gather's rays read a field as smooth as over elements of the element size.
std::vector<Rgb> inherited_radiance(const Elements& output, const Clusters& clusters, const std::vector<Rgb>& radiance,
                                    const int32_t* material, float hard_edge_angle);

/// The output elements' emission as the bake reports it (own emission plus the lamps' and the
/// world's first reflection, BakeResult): `emitted` (the output's own) plus the first reflection
/// each cluster received, `solve_emission` less `solve_emitted` (the solve elements' own).
std::vector<Rgb> inherited_emission(const Clusters& clusters, const std::vector<Rgb>& emitted,
                                    const std::vector<Rgb>& solve_emission, const std::vector<Rgb>& solve_emitted);

/// `progress` with the solve's radiance (Progress::radiance, one per solve element) given as the
/// output elements', flat over each cluster: what plan() gave a preview to draw is the output's
/// elements. `progress` itself when nothing merged.
ProgressFn output_progress(const Clusters& clusters, const ProgressFn& progress);

}  // namespace radiosity::detail
