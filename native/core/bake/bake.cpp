/// @file bake.cpp
/// @brief The uniform bake pipeline: elements, form factors (stored or on demand), solve, corners.
#include "bake/matrix_estimate.h"
#include "bake/output_pass.h"
#include "bake/pipelines.h"

#include "output/cluster_light.h"
#include "transport/small_emitters.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

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

namespace {

/// The budget of one stored matrix: progressive refinement keeps F and F^T.
std::size_t matrix_budget(const BakeSettings& settings) {
    return settings.matrix_budget_bytes / (settings.solve.method == Method::Progressive ? 2 : 1);
}

}  // namespace

std::size_t planned_matrix_bytes(const Elements& elements, const BakeSettings& settings) {
    const std::size_t bound = matrix_bytes_bound(elements.size(), settings.resolution);
    if (bound <= matrix_budget(settings)) return bound;
    return estimate_matrix(elements, row_settings(settings)).bytes;
}

bool fits_matrix_budget(std::size_t matrix_bytes, const BakeSettings& settings) {
    return matrix_bytes <= matrix_budget(settings);
}

bool stores_matrix(const Elements& elements, const BakeSettings& settings) {
    return fits_matrix_budget(planned_matrix_bytes(elements, settings), settings);
}

UniformTransport uniform_transport(const SceneInput& input, const BakeSettings& settings, const ProgressFn& progress) {
    UniformTransport transport;
    auto start = Clock::now();
    transport.build = uniform_elements(input, settings, progress);
    transport.clusters = uniform_clusters(transport.build, input, settings);
    transport.emitted = transport.build.elements.emission;
    transport.seconds_elements = seconds_since(start);
    solve_form_factors(transport, settings, progress);
    return transport;
}

void solve_form_factors(UniformTransport& transport, const BakeSettings& settings, const ProgressFn& progress) {
    transport.form_factors.reset();
    transport.seconds_form_factors = 0.0;
    transport.matrix_stored = stores_matrix(transport.solve_elements(), settings);
    if (!transport.matrix_stored) return;
    const auto start = Clock::now();
    transport.form_factors.emplace(compute_form_factors(transport.solve_elements(), row_settings(settings), progress));
    transport.seconds_form_factors = seconds_since(start);
}

void merge_again(UniformTransport& transport, Clusters clusters, const BakeSettings& settings,
                 const ProgressFn& progress) {
    transport.clusters = std::move(clusters);
    transport.kept_first_shot.reset();
    solve_form_factors(transport, settings, progress);
}

RowSettings row_settings(const BakeSettings& settings) {
    RowSettings rows;
    rows.resolution = settings.resolution;
    rows.rotations = settings.hemicube_rotations;
    rows.near_field = settings.near_field;
    return rows;
}

namespace {

/// The lamps' and the world's first reflection, rho E / pi, added to the elements' emission; each
/// traced lamp's light on an element read from `kept` where an earlier bake kept it (may be null).
void add_first_reflection(Elements& elements, const BakeSettings& settings, KeptFirstShot* kept, BakeResult& result,
                          const ProgressFn& progress) {
    auto start = Clock::now();
    if (!settings.lights.empty()) {
        LampLightThrough through;
        const SourceSignatures signatures = source_signatures(settings.lights, WorldLight());
        if (kept != nullptr)
            through = [&](std::size_t e, std::size_t l, bool fully, const std::function<Rgb()>& trace) {
                return kept->light(e, signatures.lamps[l][fully], trace);
            };
        const std::vector<Rgb> E = direct_irradiance(elements, settings.lights, through, progress);
        for (std::size_t e = 0; e < elements.size(); ++e) elements.emission[e] += elements.reflectance[e] * E[e] / M_PI;
    }
    result.seconds_lights += seconds_since(start);
    start = Clock::now();
    if (!settings.world.empty()) {
        const std::vector<Rgb> E = world_irradiance(elements, settings.world, progress);
        for (std::size_t e = 0; e < elements.size(); ++e) elements.emission[e] += elements.reflectance[e] * E[e] / M_PI;
    }
    result.seconds_world += seconds_since(start);
}

/// Small emitters, and lamps, which hemi-cubes do not see, light every element directly; the
/// solve carries only the light reflected after that, so their own emission leaves it until the
/// solve is done.
struct SmallEmitters {
    std::vector<int32_t> elements;
    std::vector<Rgb> light;  ///< their direct light on every element (empty without any)
};

SmallEmitters light_from_small_emitters(Elements& elements, const std::vector<Rgb>& emitted,
                                        const BakeSettings& settings, BakeResult& result, const ProgressFn& progress) {
    SmallEmitters small;
    for (std::size_t e = 0; e < elements.size(); ++e)
        if ((elements.area[e] < settings.direct_emitter_area || !elements.blocks(e)) && max_channel(emitted[e]) > 0.0)
            small.elements.push_back(int32_t(e));
    if (small.elements.empty()) return small;
    const auto start = Clock::now();
    small.light = detail::small_emitter_light(elements, small.elements, emitted, progress);
    for (std::size_t e = 0; e < elements.size(); ++e) elements.emission[e] += elements.reflectance[e] * small.light[e];
    for (const int32_t j : small.elements) elements.emission[j] -= emitted[j];
    result.direct_emitters += small.elements.size();
    result.seconds_direct_emitters += seconds_since(start);
    return small;
}

/// Small emitters shine again; the first reflection of their light stays out of the emission
/// reported, so that the energy balance counts it as light received (absorbed or reflected).
void restore_small_emitters(Elements& elements, const std::vector<Rgb>& emitted, const SmallEmitters& small,
                            SolveResult& solved) {
    for (const int32_t j : small.elements) {
        solved.radiance[j] += emitted[j];
        elements.emission[j] += emitted[j];
    }
    for (std::size_t e = 0; e < small.light.size(); ++e)
        elements.emission[e] -= elements.reflectance[e] * small.light[e];
}

/// The output's elements take the light solved over merged ones (cluster_light.h): `result`'s
/// radiance becomes theirs, and their emission the one reported. `solve_emitted`: the solve
/// elements' own emission.
void inherit_light(const SceneInput& input, const BakeSettings& settings, UniformTransport& transport,
                   const std::vector<Rgb>& emitted, const std::vector<Rgb>& solve_emitted, BakeResult& result) {
    const Clusters& clusters = transport.clusters;
    Elements& output = transport.build.elements;
    result.solve.radiance =
        inherited_radiance(output, clusters, result.solve.radiance, input.material, settings.hard_edge_angle);
    output.emission = inherited_emission(clusters, emitted, clusters.elements.emission, solve_emitted);
}

}  // namespace

void light_of_sources(const SceneInput& input, const BakeSettings& settings, UniformTransport& transport,
                      const std::vector<Rgb>& emitted, BakeResult& result, const ProgressFn& progress) {
    Elements& elements = transport.solve_elements();
    const std::vector<Rgb> solve_emitted = per_solve_element(transport.clusters, emitted);
    elements.emission = solve_emitted;
    add_first_reflection(elements, settings, transport.kept_first_shot.get(), result, progress);
    const SmallEmitters small = light_from_small_emitters(elements, solve_emitted, settings, result, progress);

    const std::size_t copies = settings.solve.method == Method::Progressive ? 2 : 1;
    const ProgressFn solve_progress = output_progress(transport.clusters, progress);
    result.matrix_stored = transport.matrix_stored;
    if (transport.form_factors) {
        result.matrix_nonzeros = transport.form_factors->nonzeros();
        result.matrix_bytes = copies * transport.form_factors->bytes();
        result.solve = solve(elements, *transport.form_factors, settings.solve, solve_progress);
    } else {
        HemicubeRows on_demand(elements, row_settings(settings));
        result.solve = solve(elements, on_demand, settings.solve, solve_progress);  // includes rendering rows
    }
    result.seconds_solve += result.solve.seconds;
    restore_small_emitters(elements, solve_emitted, small, result.solve);
    result.solve_elements = elements.size();
    if (transport.clusters.merged()) inherit_light(input, settings, transport, emitted, solve_emitted, result);
    output_pass(input, settings, transport.build.elements, emitted, result, progress,
                {transport.gather_hits.get(), transport.kept_direct.get()});
}

BakeResult bake_uniform(const SceneInput& input, const BakeSettings& settings, const ProgressFn& progress) {
    UniformTransport transport = uniform_transport(input, settings, progress);
    BakeResult result;
    result.seconds_elements = transport.seconds_elements;
    result.seconds_form_factors = transport.seconds_form_factors;
    light_of_sources(input, settings, transport, transport.emitted, result, progress);
    result.build = std::move(transport.build);
    return result;
}

}  // namespace detail
}  // namespace radiosity
