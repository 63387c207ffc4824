/// @file bench_elements.cpp
/// @brief Cost of build_elements with and without cutting along intersections (Google Benchmark):
/// a 1e6-triangle terrain that intersects nothing, and the Cornell box. Argument: cut off (0) or on (1).
/// And of interpolate_corners on the terrain's 1e6 elements (the last stage of every bake).

#include "geometry/scene.h"
#include "output/interpolation.h"
#include "testing/test_util.h"

#include <benchmark/benchmark.h>

#include <cmath>

using namespace radiosity;

namespace {

/// A rolling height field of 500 x 1000 quads, each split into two triangles over shared vertices:
/// 1e6 triangles, none coplanar with its neighbours, none passing through another.
const test::SceneArrays& terrain() {
    static const test::SceneArrays scene = [] {
        test::SceneArrays s;
        const int nx = 500, ny = 1000;
        for (int j = 0; j <= ny; ++j)
            for (int i = 0; i <= nx; ++i) {
                const float x = 0.01f * float(i), y = 0.01f * float(j);
                s.positions.insert(s.positions.end(), {x, y, 0.05f * std::sin(7.0f * x) * std::cos(5.0f * y)});
            }
        auto vertex = [&](int i, int j) { return j * (nx + 1) + i; };
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                for (const int32_t v : {vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1)})
                    s.corner_vertices.push_back(v);
                s.face_offsets.push_back(static_cast<int32_t>(s.corner_vertices.size()));
                for (const int32_t v : {vertex(i, j), vertex(i + 1, j + 1), vertex(i, j + 1)})
                    s.corner_vertices.push_back(v);
                s.face_offsets.push_back(static_cast<int32_t>(s.corner_vertices.size()));
            }
        const std::size_t faces = s.face_offsets.size() - 1;
        s.reflectance.assign(3 * faces, 0.5f);
        s.emission.assign(3 * faces, 0.0f);
        s.material.assign(faces, 0);
        return s;
    }();
    return scene;
}

void build(benchmark::State& state, const test::SceneArrays& scene, float element_size) {
    ElementLimits limits;
    limits.cut_intersections = state.range(0) != 0;
    std::size_t elements = 0;
    for (auto _ : state) {
        const BuildResult r = build_elements(scene.input(), element_size, limits);
        elements = r.elements.size();
        benchmark::DoNotOptimize(elements);
    }
    state.counters["polygons"] = double(scene.face_offsets.size() - 1);
    state.counters["elements"] = double(elements);
}

void terrain_elements(benchmark::State& state) { build(state, terrain(), 0.0f); }

void cornell_elements(benchmark::State& state) {
    static const test::SceneArrays scene = test::cornell_box();
    build(state, scene, 0.05f);
}

void terrain_corner_colours(benchmark::State& state) {
    const BuildResult built = build_elements(terrain().input(), 0.0f, ElementLimits{});
    std::vector<Rgb> radiance(built.elements.size());
    for (std::size_t e = 0; e < radiance.size(); ++e) radiance[e] = Rgb(1.0 + built.elements.centre[e].x);
    for (auto _ : state) {
        const CornerColors colors = interpolate_corners(built.elements, radiance, terrain().material.data(), 0.5f);
        benchmark::DoNotOptimize(colors.input_corner.data());
    }
    state.counters["elements"] = double(built.elements.size());
}

}  // namespace

BENCHMARK(terrain_corner_colours)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(terrain_elements)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(cornell_elements)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
