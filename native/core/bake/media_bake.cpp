/// @file media_bake.cpp
/// @brief bake_with_media(): the surface pipeline with zones in the system.
#include "bake/media_bake.h"

#include "bake/pipelines.h"
#include "geometry/surface_textures.h"
#include "media/lamps_in_media.h"
#include "media/zonal_solver.h"

#include <chrono>

namespace radiosity {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

/// The lamps' first reflection, rho E / pi, joins the elements' emission and their first
/// scattering, Omega H, the zones' emitted radiance (lamps_in_media.h).
void add_first_shot(Elements& elements, const std::vector<Medium>& media, Zones& zones, const Lights& lights,
                    const ProgressFn& progress) {
    if (lights.empty()) return;
    const LampsThroughMedia lamps = lamps_through_media(elements, lights, zones, MediumTracer(media, zones), progress);
    for (std::size_t e = 0; e < elements.size(); ++e)
        elements.emission[e] += elements.reflectance[e] * lamps.element_irradiance[e] / M_PI;
    for (std::size_t k = 0; k < zones.size(); ++k) zones.emitted[k] += zones.albedo[k] * lamps.zone_incident[k];
}

}  // namespace

ZonalBakeResult bake_with_media(const SceneInput& input, const std::vector<Medium>& media, const BakeSettings& settings,
                                int zone_resolution, const ProgressFn& progress, int grid_subdivision,
                                int max_block_level) {
    ZonalBakeResult result;
    BakeResult& bake = result.surfaces;

    auto start = Clock::now();
    result.zones = build_zones(media, max_block_level);
    result.seconds_zones = seconds_since(start);

    start = Clock::now();
    bake.build = detail::media_elements(input, settings);
    Elements& elements = bake.build.elements;
    bake.seconds_elements = seconds_since(start);

    const std::vector<Rgb> emitted = elements.emission;
    start = Clock::now();
    add_first_shot(elements, media, result.zones, settings.lights, progress);
    bake.seconds_lights = seconds_since(start);

    start = Clock::now();
    const bool progressive = settings.solve.method == Method::Progressive;
    ZonalFactorSettings factor_settings;
    factor_settings.surface_resolution = settings.resolution;
    factor_settings.zone_resolution = zone_resolution;
    factor_settings.budget_bytes = settings.matrix_budget_bytes / (progressive ? 2 : 1);
    ZonalMatrix R = compute_exchange_factors(elements, media, result.zones, factor_settings, progress);
    enforce_reciprocity(R, zonal_weights(elements, result.zones));
    bake.matrix_stored = true;
    bake.matrix_nonzeros = R.nonzeros();
    bake.matrix_bytes = (progressive ? 2 : 1) * R.bytes();
    bake.seconds_form_factors = seconds_since(start);

    SolveResult solved = solve_zonal(elements, result.zones, R, settings.solve, progress);
    const std::size_t n = elements.size();
    result.zone_radiance.assign(solved.radiance.begin() + n, solved.radiance.end());
    result.zone_incident.assign(result.zones.size(), Rgb(0.0));
    for (std::size_t k = 0; k < result.zones.size(); ++k)
        for (int64_t e = R.row_start[n + k]; e < R.row_start[n + k + 1]; ++e)
            result.zone_incident[k] += R.value(e) * solved.radiance[R.col[e]];
    solved.radiance.resize(n);
    bake.solve = std::move(solved);
    bake.seconds_solve = bake.solve.seconds;

    start = Clock::now();
    bake.colors = interpolate_corners(elements, bake.solve.radiance, input.material, settings.hard_edge_angle);
    bake.light_colors = interpolate_corners(elements, detail::light_arriving(elements, bake.solve.radiance, emitted),
                                            input.material, settings.hard_edge_angle);
    // Textured faces show their texel at each corner, lit by the light arriving there.
    if (input.textures) detail::texture_corners(input, elements, bake.light_colors, bake.colors);
    bake.seconds_interpolate = seconds_since(start);

    for (std::size_t i = 0; i < media.size(); ++i)
        result.grids.push_back(
            medium_grids(media[i], voxel_radiance(media[i], i, result.zones, result.zone_radiance), grid_subdivision));
    return result;
}

}  // namespace radiosity
