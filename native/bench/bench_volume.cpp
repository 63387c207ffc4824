/// @file bench_volume.cpp
/// @brief Cost of the zonal method against zone count (Google Benchmark): the Cornell box with about
/// 10k elements, filled with fog split into n^3 zones (n = 16, 32, 64).
///
/// zonal_rows: time and nonzeros per row, measured on one thread over a fixed sample of element
/// rows and zone rows spread over the scene; totals (time on one core, matrix bytes) extrapolated
/// from them. zonal_bake: the full bake_with_media (both cores), where its matrix fits in memory.
/// Settings: element hemi-cubes at resolution 64, zone cubes at 32 (6144 rays), grey fog
/// K_t = 2 / m, albedo 0.8, ceiling lamp 15.

#include "radiosity/zonal_bake.h"
#include "test_util.h"

#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <chrono>
#include <cmath>

using namespace radiosity;

namespace {

constexpr int kSurfaceResolution = 64, kZoneResolution = 32;

/// Cornell box max_edge giving about `target` elements.
float edge_for(const test::SceneArrays& scene, int target) {
    float lo = 0.001f, hi = 1.0f;
    for (int step = 0; step < 30; ++step) {
        const float mid = std::sqrt(lo * hi);
        (build_elements(scene.input(), mid).elements.size() > std::size_t(target) ? lo : hi) = mid;
    }
    return hi;
}

/// The box [0, 1]^3 full of grey fog, n^3 voxels.
Medium fog(int n) {
    Medium m(Vec3(0.0f), 1.0f / n, {n, n, n});
    for (std::size_t v = 0; v < m.voxel_count(); ++v) m.set(v, principled_volume(Rgb(0.8), 2.0, Rgb(0.0), 0.0, Rgb(0.0)));
    return m;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void zonal_rows(benchmark::State& state) {
    const int n = static_cast<int>(state.range(0));
    const test::SceneArrays scene = test::cornell_box();
    const Elements elements = build_elements(scene.input(), edge_for(scene, 10000)).elements;
    const std::vector<Medium> media{fog(n)};
    const Zones zones = build_zones(media);
    const MediumTracer tracer(media, zones);
    ZonalFactorSettings settings;
    settings.surface_resolution = kSurfaceResolution;
    settings.zone_resolution = kZoneResolution;
    ZonalRowRenderer renderer(elements, zones, tracer, settings);
    const std::size_t sample = 48;
    ZonalRow row;
    double element_seconds = 0, zone_seconds = 0, element_nonzeros = 0, zone_nonzeros = 0;
    std::size_t rounds = 0;
    for (auto _ : state) {
        auto start = std::chrono::steady_clock::now();
        for (std::size_t s = 0; s < sample; ++s) {
            renderer.row(static_cast<int32_t>(s * (elements.size() / sample)), row);
            element_nonzeros += double(row.col.size());
        }
        element_seconds += seconds_since(start);
        start = std::chrono::steady_clock::now();
        for (std::size_t s = 0; s < sample; ++s) {
            renderer.row(static_cast<int32_t>(elements.size() + s * (zones.size() / sample)), row);
            zone_nonzeros += double(row.col.size());
        }
        zone_seconds += seconds_since(start);
        ++rounds;
    }
    const double rows = double(sample * rounds), ne = double(elements.size()), nz = double(zones.size());
    const double per_element = element_seconds / rows, per_zone = zone_seconds / rows;
    const double nnz_element = element_nonzeros / rows, nnz_zone = zone_nonzeros / rows;
    state.counters["elements"] = ne;
    state.counters["zones"] = nz;
    state.counters["ms_per_element_row"] = per_element * 1e3;
    state.counters["ms_per_zone_row"] = per_zone * 1e3;
    state.counters["nnz_per_element_row"] = nnz_element;
    state.counters["nnz_per_zone_row"] = nnz_zone;
    state.counters["factors_core_s"] = ne * per_element + nz * per_zone;  // one core
    state.counters["matrix_GB"] = ((ne + nz) * 8.0 + (ne * nnz_element + nz * nnz_zone) * 8.0) / 1e9;
}

void zonal_bake(benchmark::State& state) {
    const int n = static_cast<int>(state.range(0));
    const test::SceneArrays scene = test::cornell_box();
    BakeSettings settings;
    settings.element_size = edge_for(scene, 10000);
    settings.resolution = kSurfaceResolution;
    settings.matrix_budget_bytes = std::size_t(8) << 30;
    const std::vector<Medium> media{fog(n)};
    ZonalBakeResult result;
    for (auto _ : state) result = bake_with_media(scene.input(), media, settings, kZoneResolution);
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    state.counters["elements"] = double(result.surfaces.build.elements.size());
    state.counters["zones"] = double(result.zones.size());
    state.counters["factors_s"] = result.surfaces.seconds_form_factors;
    state.counters["solve_s"] = result.surfaces.seconds_solve;
    state.counters["iterations"] = result.surfaces.solve.iterations;
    state.counters["matrix_GB"] = double(result.surfaces.matrix_bytes) / 1e9;
    state.counters["peak_rss_GB"] = double(usage.ru_maxrss) / 1e6;  // ru_maxrss is in KiB on Linux
}

}  // namespace

BENCHMARK(zonal_rows)->Arg(16)->Arg(32)->Arg(64)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK(zonal_bake)->Arg(16)->Iterations(1)->Unit(benchmark::kSecond);
