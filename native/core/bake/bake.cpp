/// @file bake.cpp
/// @brief The uniform bake pipeline: elements, form factors (stored or on demand), solve, corners.
#include "bake/output_pass.h"
#include "bake/pipelines.h"

#include "transport/small_emitters.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace radiosity {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

}  // namespace

std::size_t matrix_bytes_bound(std::size_t element_count, int resolution) {
    const std::size_t N = static_cast<std::size_t>(std::max(resolution, 0));
    return element_count * std::min(element_count, 3 * N * N) * (sizeof(float) + sizeof(int32_t));
}

namespace detail {

std::vector<Rgb> light_arriving(const Elements& elements, const std::vector<Rgb>& radiance,
                                const std::vector<Rgb>& emitted) {
    std::vector<Rgb> light(elements.size(), Rgb(0.0));
    for (std::size_t e = 0; e < elements.size(); ++e)
        for (int c = 0; c < 3; ++c)
            if (elements.reflectance[e][c] > 0.0)
                light[e][c] = std::max(0.0, (radiance[e][c] - emitted[e][c]) / elements.reflectance[e][c]);
    return light;
}

bool stores_matrix(std::size_t element_count, const BakeSettings& settings) {
    const std::size_t copies = settings.solve.method == Method::Progressive ? 2 : 1;
    return matrix_bytes_bound(element_count, settings.resolution) <= settings.matrix_budget_bytes / copies;
}

BakeResult bake_uniform(const SceneInput& input, const BakeSettings& settings, const ProgressFn& progress) {
    BakeResult result;

    auto start = Clock::now();
    result.build = uniform_elements(input, settings, progress);
    Elements& elements = result.build.elements;
    result.seconds_elements = seconds_since(start);

    // The polygons' own emission, before the lamps' and the world's first reflection join it (the final gather
    // counts emission as direct light and everything else the solve found as indirect).
    const std::vector<Rgb> emitted = elements.emission;
    start = Clock::now();
    if (!settings.lights.empty()) {
        const std::vector<Rgb> E = direct_irradiance(elements, settings.lights, progress);
        for (std::size_t e = 0; e < elements.size(); ++e) elements.emission[e] += elements.reflectance[e] * E[e] / M_PI;
    }
    result.seconds_lights = seconds_since(start);
    start = Clock::now();
    if (!settings.world.empty()) {
        const std::vector<Rgb> E = world_irradiance(elements, settings.world, progress);
        for (std::size_t e = 0; e < elements.size(); ++e) elements.emission[e] += elements.reflectance[e] * E[e] / M_PI;
    }
    result.seconds_world = seconds_since(start);

    // Small emitters, and lamps, which hemi-cubes do not see, light every element directly; the
    // solve carries only the light reflected after that, so their own emission leaves it until the
    // solve is done.
    std::vector<int32_t> small;
    for (std::size_t e = 0; e < elements.size(); ++e)
        if ((elements.area[e] < settings.direct_emitter_area || !elements.blocks(e)) && max_channel(emitted[e]) > 0.0)
            small.push_back(int32_t(e));
    std::vector<Rgb> small_light;
    if (!small.empty()) {
        start = Clock::now();
        small_light = detail::small_emitter_light(elements, small, emitted, progress);
        for (std::size_t e = 0; e < elements.size(); ++e)
            elements.emission[e] += elements.reflectance[e] * small_light[e];
        for (const int32_t j : small) elements.emission[j] -= emitted[j];
        result.direct_emitters = small.size();
        result.seconds_direct_emitters = seconds_since(start);
    }

    const std::size_t copies = settings.solve.method == Method::Progressive ? 2 : 1;
    result.matrix_stored = stores_matrix(elements.size(), settings);
    RowSettings rows;
    rows.resolution = settings.resolution;
    rows.rotations = settings.hemicube_rotations;
    rows.near_field = settings.near_field;
    start = Clock::now();
    if (result.matrix_stored) {
        const SparseMatrix F = compute_form_factors(elements, rows, progress);
        result.matrix_nonzeros = F.nonzeros();
        result.matrix_bytes = copies * F.bytes();
        result.seconds_form_factors = seconds_since(start);
        result.solve = solve(elements, F, settings.solve, progress);
    } else {
        HemicubeRows on_demand(elements, rows);
        result.solve = solve(elements, on_demand, settings.solve, progress);  // includes rendering rows
    }
    result.seconds_solve = result.solve.seconds;
    // Small emitters shine again; the first reflection of their light stays out of the emission
    // reported, so that the energy balance counts it as light received (absorbed or reflected).
    for (const int32_t j : small) {
        result.solve.radiance[j] += emitted[j];
        elements.emission[j] += emitted[j];
    }
    for (std::size_t e = 0; e < small_light.size(); ++e)
        elements.emission[e] -= elements.reflectance[e] * small_light[e];

    output_pass(input, settings, elements, emitted, result, progress);
    return result;
}

}  // namespace detail
}  // namespace radiosity
