/// @file output_pass.h
/// @brief What every surface bake writes at the output corners, whichever method solved it
/// (internal; bake.h).
#pragma once

#include "bake/bake.h"
#include "output/final_gather.h"

namespace radiosity::detail {

/// The output corners of a solved bake: the solution's radiance and the light arriving
/// interpolated to the corners, then, with `settings.final_gather`, each corner gathered at the
/// corner itself (output/final_gather.h), then the textured faces' texels lit by the light
/// arriving. `elements` and `result.solve.radiance` are the solution (the uniform elements or the
/// hierarchy's leaves); `emitted` each element's own emission, without the lamps' and the world's
/// first reflection. Sets result.colors, light_colors and the gather's counts, statistics and time.
/// `kept`: what earlier gathers over these elements kept, read and added to (final_gather.h's GatherKept).
void output_pass(const SceneInput& input, const BakeSettings& settings, const Elements& elements,
                 const std::vector<Rgb>& emitted, BakeResult& result, const ProgressFn& progress,
                 const GatherKept& kept = {});

}  // namespace radiosity::detail
