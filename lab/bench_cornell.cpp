/// @file bench_cornell.cpp
/// @brief Hemi-cube cost, matrix size, solve time and analytic errors on the Cornell box (Google Benchmark).
///
/// Per-hemi-cube time is measured on one thread over a fixed sample of elements spread over the
/// scene (every k-th element), so it is the cost per hemi-cube per core. For the matrix counters
/// the full matrix is computed once (outside the timing) up to 10k elements; at 40k the nonzeros
/// are estimated from the sampled rows instead of storing the matrix. Methods: 0 Gauss-Seidel,
/// 1 Jacobi, 2 progressive refinement.

#include "solve/solver.h"
#include "testing/test_util.h"

#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <map>

using namespace radiosity;

namespace {

/// Cornell box elements, max_edge chosen so that the count is close to `target`.
const Elements& cornell_elements(int target) {
    static std::map<int, Elements> cache;
    auto found = cache.find(target);
    if (found != cache.end()) return found->second;
    static const test::SceneArrays scene = test::cornell_box();
    float lo = 0.001f, hi = 1.0f;  // the count falls as max_edge grows
    for (int step = 0; step < 30; ++step) {
        const float mid = std::sqrt(lo * hi);
        (build_elements(scene.input(), mid).elements.size() > std::size_t(target) ? lo : hi) = mid;
    }
    return cache.emplace(target, build_elements(scene.input(), hi).elements).first->second;
}

void hemicube_cost(benchmark::State& state) {
    const Elements& e = cornell_elements(static_cast<int>(state.range(0)));
    const int resolution = static_cast<int>(state.range(1));
    const std::size_t sample = std::min<std::size_t>(e.size(), 256), stride = e.size() / sample;
    Hemicube hemicube(CubeWeights::make(resolution));
    SparseRow row;
    std::size_t nonzeros = 0, rendered = 0;
    double seconds = 0.0;
    for (auto _ : state) {
        const auto start = std::chrono::steady_clock::now();
        for (std::size_t k = 0; k < sample; ++k) {
            const auto i = static_cast<int32_t>(k * stride);
            hemicube.render_hemisphere(e, e.centre[i], e.normal[i], i);
            hemicube.accumulate(hemicube.weights().form_factor, row);
            nonzeros += row.col.size();
        }
        rendered += sample;
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    const double per_row = double(nonzeros) / double(rendered);
    state.counters["elements"] = double(e.size());
    state.counters["us_per_hemicube"] = seconds * 1e6 / double(rendered);
    state.counters["nnz_per_row"] = per_row;
    double bytes = 0.0;
    if (e.size() <= 10000) {
        bytes = double(compute_form_factors(e, resolution).bytes());
    } else {  // estimated from the sampled rows
        bytes = double(e.size() + 1) * sizeof(int64_t) + double(e.size()) * per_row * (sizeof(int32_t) + sizeof(float));
    }
    state.counters["matrix_MB"] = bytes / (1024.0 * 1024.0);
}

/// Solve time per method on a stored matrix (resolution 128), tolerance 1e-4; every method solves
/// the same system (progressive refinement shoots the stored matrix's columns).
void solve_time(benchmark::State& state) {
    const Elements& e = cornell_elements(static_cast<int>(state.range(0)));
    static std::map<int, SparseMatrix> matrices;
    auto found = matrices.find(static_cast<int>(state.range(0)));
    if (found == matrices.end())
        found = matrices.emplace(static_cast<int>(state.range(0)), compute_form_factors(e, 128)).first;
    SolveSettings settings;
    settings.method = static_cast<Method>(state.range(1));
    SolveResult result;
    for (auto _ : state) result = solve(e, found->second, settings);
    state.counters["iterations"] = result.iterations;
    state.counters["residual"] = result.residual;
}

/// Point factor from the centre of element `from` to every element of polygon `to`.
double point_factor(Hemicube& hemicube, const Elements& e, int32_t from, int32_t to) {
    hemicube.render_hemisphere(e, e.centre[from], e.normal[from], from);
    SparseRow row;
    hemicube.accumulate(hemicube.weights().form_factor, row);
    double f = 0.0;
    for (std::size_t k = 0; k < row.col.size(); ++k) f += e.polygon[row.col[k]] == to ? row.val[k] : 0.0;
    return f;
}

/// Area factor from polygon `from` (split into 16 x 16 elements) to polygon `to`.
double area_factor(Hemicube& hemicube, const Elements& e, int32_t from, int32_t to) {
    double flux = 0.0, area = 0.0;
    for (std::size_t i = 0; i < e.size(); ++i)
        if (e.polygon[i] == from) {
            flux += e.area[i] * point_factor(hemicube, e, static_cast<int32_t>(i), to);
            area += e.area[i];
        }
    return flux / area;
}

/// Errors against Howell's closed forms at one resolution (point: one element per square; area:
/// 16 x 16 elements, the receiving square's elements summed).
void analytic_errors(benchmark::State& state) {
    const int n = static_cast<int>(state.range(0));
    const Elements opposed = build_elements(test::opposed_unit_squares(1.0f).input(), 0.0f).elements;
    const Elements perpendicular = build_elements(test::perpendicular_unit_squares().input(), 0.0f).elements;
    const Elements opposed_fine = build_elements(test::opposed_unit_squares(1.0f).input(), 1.0f / 16).elements;
    const Elements perpendicular_fine = build_elements(test::perpendicular_unit_squares().input(), 1.0f / 16).elements;
    Hemicube hemicube(CubeWeights::make(n));
    double errors[4] = {};
    for (auto _ : state) {
        errors[0] = point_factor(hemicube, opposed, 1, 0) - 0.239456;
        errors[1] = point_factor(hemicube, perpendicular, 0, 1) - 0.190136;
        errors[2] = area_factor(hemicube, opposed_fine, 1, 0) - 0.19982;
        errors[3] = area_factor(hemicube, perpendicular_fine, 0, 1) - 0.20004;
    }
    state.counters["opposed_point"] = errors[0];
    state.counters["perpendicular_point"] = errors[1];
    state.counters["opposed_area"] = errors[2];
    state.counters["perpendicular_area"] = errors[3];
}

}  // namespace

BENCHMARK(analytic_errors)->ArgName("res")->Arg(64)->Arg(128)->Arg(256)->Iterations(1)->Unit(benchmark::kMillisecond);

BENCHMARK(solve_time)
    ->ArgNames({"elements", "method"})
    ->ArgsProduct({{1000, 4000}, {0, 1, 2}})
    ->Unit(benchmark::kMillisecond);

BENCHMARK(hemicube_cost)
    ->ArgNames({"elements", "res"})
    ->ArgsProduct({{1000, 4000, 10000, 40000}, {64, 128, 256}})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
