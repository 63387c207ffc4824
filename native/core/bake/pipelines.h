/// @file pipelines.h
/// @brief The pipelines behind bake() and the elements each solves (internal; bake.h).
#pragma once

#include "bake/bake.h"

namespace radiosity::detail {

/// The uniform bake's elements: at most `element_size`, cut along intersections and contacts.
/// Progress phases as build_elements'.
BuildResult uniform_elements(const SceneInput& input, const BakeSettings& settings, const ProgressFn& progress = {});

/// The media bake's elements: at most `element_size`, cut along intersections. The zonal exchange
/// has no direct path for lamps (small_emitters.h): their quads stay in the factors, lit and
/// blocking like any emitter (front-only still).
BuildResult media_elements(const SceneInput& input, const BakeSettings& settings);

/// Each element's light arriving, irradiance / pi, from B = E + rho H: H = (B - E) / rho per
/// channel, 0 where rho is 0 (BakeResult::light_colors). `emitted`: the elements' own emission.
std::vector<Rgb> light_arriving(const Elements& elements, const std::vector<Rgb>& radiance,
                                const std::vector<Rgb>& emitted);

/// The hierarchy's settings from the bake's (bake.h's HierarchicalSettings says which it takes).
HierarchySettings hierarchy_settings(const BakeSettings& settings);

/// Whether the uniform bake stores F: computed in parallel and read cheaply by every sweep or
/// shot, with F^T too for progressive refinement's exact columns. Beyond the budget, rows are
/// rendered on demand (memory O(n)).
bool stores_matrix(std::size_t element_count, const BakeSettings& settings);

/// The uniform bake (see bake.h): stores F when it fits the budget, else renders rows on demand.
BakeResult bake_uniform(const SceneInput& input, const BakeSettings& settings, const ProgressFn& progress);

}  // namespace radiosity::detail
