/// @file output_pass.cpp
/// @brief Interpolation, final gather and textures at the output corners (output_pass.h).
#include "bake/output_pass.h"

#include "bake/pipelines.h"
#include "geometry/surface_textures.h"
#include "output/final_gather.h"

#include <chrono>

namespace radiosity::detail {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

}  // namespace

void output_pass(const SceneInput& input, const BakeSettings& settings, const Elements& elements,
                 const std::vector<Rgb>& emitted, BakeResult& result, const ProgressFn& progress,
                 const GatherKept& kept) {
    auto start = Clock::now();
    const std::vector<Rgb>& radiance = result.solve.radiance;
    result.colors = interpolate_corners(elements, radiance, input.material, settings.hard_edge_angle);
    result.light_colors = interpolate_corners(elements, light_arriving(elements, radiance, emitted), input.material,
                                              settings.hard_edge_angle);
    result.seconds_interpolate += seconds_since(start);

    if (settings.final_gather.enabled) {
        start = Clock::now();
        result.gather_cost =
            final_gather(elements, emitted, radiance, settings.lights, settings.world, settings.final_gather,
                         input.material, input.face_offsets, input.face_count, settings.hard_edge_angle, result.colors,
                         result.light_colors, progress, &result.gather_statistics.emplace(), kept);
        result.gathered_points = result.gather_cost.gathered;
        result.interpolated_points = result.gather_cost.interpolated;
        result.buried_points = result.gather_cost.buried;
        result.seconds_gather = seconds_since(start);
    }
    // Textured faces show their texel at each corner, lit by the light arriving there.
    if (input.textures) texture_corners(input, elements, result.light_colors, result.colors);
}

}  // namespace radiosity::detail
