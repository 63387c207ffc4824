/// @file bench_volume.cpp
/// @brief Cost of the zonal method against zone count (Google Benchmark): the Cornell box with about
/// 10k elements, filled with fog split into n^3 zones (n = 16, 32, 64).
///
/// zonal_rows: time and nonzeros per row, measured on one thread over a fixed sample of element
/// rows and zone rows spread over the scene; totals (time on one core, matrix bytes) extrapolated
/// from them. zonal_bake: the full bake_with_media (both cores), where its matrix fits in memory.
/// zonal_merge: the 16^3 bake with uniform blocks merged (the default) and without, in one run:
/// each one's time, matrix and peak memory, their ratios, and how far the walls moved.
/// Settings: element hemi-cubes at resolution 64, zone cubes at 32 (6144 rays), grey fog
/// K_t = 2 / m, albedo 0.8, ceiling lamp 15.

#include "bake/media_bake.h"
#include "testing/test_util.h"

#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <string>

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
    for (std::size_t v = 0; v < m.voxel_count(); ++v)
        m.set(v, principled_volume(Rgb(0.8), 2.0, Rgb(0.0), 0.0, Rgb(0.0)));
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
    // One zone per voxel: the n^3 zones this measures (zonal_merge shows merging).
    for (auto _ : state) result = bake_with_media(scene.input(), media, settings, kZoneResolution, {}, 1, 0);
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

/// Resets the process's peak resident memory (Linux: "5" to /proc/self/clear_refs), so each bake's
/// own peak can be read after it.
void reset_peak_memory() { std::ofstream("/proc/self/clear_refs") << "5"; }

/// Peak resident memory since the last reset, GB (VmHWM of /proc/self/status).
double peak_memory_GB() {
    std::ifstream status("/proc/self/status");
    for (std::string line; std::getline(status, line);)
        if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) * 1024.0 / 1e9;  // kB
    return 0.0;
}

void zonal_merge(benchmark::State& state) {
    const test::SceneArrays scene = test::cornell_box();
    BakeSettings settings;
    settings.element_size = edge_for(scene, 10000);
    settings.resolution = kSurfaceResolution;
    settings.matrix_budget_bytes = std::size_t(8) << 30;
    const std::vector<Medium> media{fog(16)};
    struct Run {
        ZonalBakeResult result;
        double seconds = 0.0, peak_GB = 0.0;
    } runs[2];  // merged (the default), then one zone per voxel
    for (auto _ : state)
        for (int i = 0; i < 2; ++i) {
            reset_peak_memory();
            const auto start = std::chrono::steady_clock::now();
            runs[i].result = bake_with_media(scene.input(), media, settings, kZoneResolution, {}, 1,
                                             i == 0 ? kDefaultMaxBlockLevel : 0);
            runs[i].seconds = seconds_since(start);
            runs[i].peak_GB = peak_memory_GB();
        }
    const char* name[2] = {"merged_", "voxels_"};
    for (int i = 0; i < 2; ++i) {
        const ZonalBakeResult& r = runs[i].result;
        const std::string p = name[i];
        state.counters[p + "zones"] = double(r.zones.size());
        state.counters[p + "bake_s"] = runs[i].seconds;
        state.counters[p + "factors_s"] = r.surfaces.seconds_form_factors;
        state.counters[p + "solve_s"] = r.surfaces.seconds_solve;
        state.counters[p + "matrix_GB"] = double(r.surfaces.matrix_bytes) / 1e9;
        state.counters[p + "peak_rss_GB"] = runs[i].peak_GB;
    }
    state.counters["elements"] = double(runs[0].result.surfaces.build.elements.size());
    state.counters["time_ratio"] = runs[0].seconds / runs[1].seconds;
    state.counters["matrix_ratio"] =
        double(runs[0].result.surfaces.matrix_bytes) / double(runs[1].result.surfaces.matrix_bytes);
    state.counters["peak_rss_ratio"] = runs[0].peak_GB / runs[1].peak_GB;
    // How far merging moved the walls (red channel), relative to their area-weighted mean radiance:
    // the mean difference, and the worst element's (relative to its own radiance it is meaningless
    // on the nearly black floor under the blocks, where fog fills the blocks' insides).
    const Elements& e = runs[0].result.surfaces.build.elements;
    const std::vector<Rgb>&a = runs[0].result.surfaces.solve.radiance, &b = runs[1].result.surfaces.solve.radiance;
    double difference = 0.0, total = 0.0, area = 0.0, worst = 0.0;
    for (std::size_t i = 0; i < e.size(); ++i) {
        difference += e.area[i] * std::abs(a[i].r - b[i].r);
        total += e.area[i] * b[i].r;
        area += e.area[i];
        worst = std::max(worst, std::abs(a[i].r - b[i].r));
    }
    state.counters["walls_mean_difference"] = difference / total;
    state.counters["walls_worst_difference"] = worst / (total / area);
}

}  // namespace

BENCHMARK(zonal_rows)->Arg(16)->Arg(32)->Arg(64)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK(zonal_bake)->Arg(16)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK(zonal_merge)->Iterations(1)->Unit(benchmark::kSecond);
