#include "hierarchy_accuracy.h"

#include "bake/bake.h"
#include "charts.h"
#include "hierarchy/hierarchy.h"
#include "hierarchy_error.h"
#include "hierarchy_scenes.h"

#include <cstdio>
#include <fstream>

namespace radiosity::charts {
namespace {

Baked bake_uniform(const LitScene& scene, float size, int resolution, double tolerance) {
    BakeSettings s;
    s.element_size = size;
    s.resolution = resolution;
    s.solve.tolerance = tolerance;
    s.lights = scene.lights;
    const auto start = std::chrono::steady_clock::now();
    BakeResult r = bake(scene.arrays.input(), s);
    Baked b;
    b.seconds = seconds_since(start);
    b.elements = b.output_elements = r.build.elements.size();
    b.mesh = std::move(r.build.elements);
    b.radiance = std::move(r.solve.radiance);
    b.corners = std::move(r.colors.element_corner);
    return b;
}

/// Area-weighted mean of (r + g + b) / 3 over each of the first `count` input polygons.
std::vector<double> polygon_means(const Elements& mesh, const std::vector<Rgb>& radiance, int count) {
    std::vector<double> power(count, 0.0), area(count, 0.0);
    for (std::size_t e = 0; e < mesh.size(); ++e) {
        if (mesh.polygon[e] >= count) continue;
        power[mesh.polygon[e]] += mesh.area[e] * (radiance[e].r + radiance[e].g + radiance[e].b) / 3.0;
        area[mesh.polygon[e]] += mesh.area[e];
    }
    for (int p = 0; p < count; ++p) power[p] /= area[p];
    return power;
}

}  // namespace

Baked bake_hierarchy(const LitScene& scene, float min_size, int lamp_levels, double refine_tolerance, double tolerance,
                     int rounds) {
    HierarchySettings s;
    s.min_element_size = min_size;
    s.lamp_detail_levels = lamp_levels;
    s.refine_tolerance = refine_tolerance;
    s.tolerance = tolerance;
    s.max_rounds = rounds;
    s.lights = scene.lights;
    const auto start = std::chrono::steady_clock::now();
    HierarchyResult r = bake_hierarchical(scene.arrays.input(), s);
    Baked b;
    b.seconds = seconds_since(start);
    b.elements = r.stats.leaves;
    b.output_elements = r.output.size();
    b.links = r.stats.links;
    b.mesh = std::move(r.output);
    b.radiance = std::move(r.output_radiance);
    b.corners = std::move(r.colors.element_corner);
    return b;
}

void cornell_wall_means() {
    const LitScene scene{test::cornell_box(), {}, 0.0f};
    const int walls = 6;  // floor, ceiling and the four walls come first
    auto print = [&](const char* method, double parameter, const Baked& b) {
        std::printf("%-9s %-6g %6.1f s ", method, parameter, b.seconds);
        for (double mean : polygon_means(b.mesh, b.radiance, walls)) std::printf(" %.5f", mean);
        std::printf("\n");
        std::fflush(stdout);
    };
    std::printf("method    param   seconds   mean radiance of polygons 0-%d\n", walls - 1);
    for (float size : {0.05f, 0.025f})
        for (int resolution : {128, 256, 512}) {
            std::printf("uniform %.3f m, ", size);
            print("hemicube", resolution, bake_uniform(scene, size, resolution, 1e-6));
        }
    for (double tolerance : {0.005, 0.002}) {
        std::printf("hierarchy 0.025 m, ");
        print("refine", tolerance, bake_hierarchy(scene, 0.025f, 0, tolerance, 1e-6, 12));
    }
}

std::vector<AccuracyCase> accuracy_cases() {
    // Hierarchy series: leaves down to the size of the finest uniform mesh the old charts had
    // (lamp detail two levels finer), and leaves four times coarser with lamp detail four levels
    // finer: the same finest lamp detail from far fewer links.
    std::vector<AccuracyCase> cases;
    cases.push_back({"cornell",
                     {test::cornell_box(), {}, 0.0f},
                     {0.2f, 0.1f, 0.07f, 0.05f},
                     {{"hierarchy", 0.05f, 2}, {"hierarchy_coarse", 0.2f, 4}},
                     {0.2, 0.1, 0.05, 0.02, 0.01},
                     0.025f,
                     512,
                     0.004f});
    cases.push_back({"shadow_room",
                     shadow_room(),
                     {0.4f, 0.2f, 0.14f, 0.1f, 0.07f, 0.05f},
                     {{"hierarchy", 0.1f, 2}, {"hierarchy_coarse", 0.4f, 4}},
                     {0.2, 0.1, 0.05, 0.02, 0.01},
                     0.05f,
                     256,
                     0.01f});
    return cases;
}

HierarchyReference hierarchy_reference(const AccuracyCase& c, const SceneInput& input, const Samples& samples) {
    HierarchyReference r;
    r.baked = bake_hierarchy(c.scene, c.reference_size, 0, 0.005, 1e-6, 12);
    r.lamp = lamp_light_at(samples, r.baked.mesh, c.scene.lights);
    r.colours = reference_colours(samples, r.baked.mesh, r.baked.radiance, input.material, r.lamp, r.unlocated);
    return r;
}

void accuracy(const std::string& csv_path) {
    const std::vector<AccuracyCase> cases = accuracy_cases();
    std::ofstream csv(csv_path);
    csv << "scene,method,parameter,min_size,lamp_levels,elements,output_elements,links,seconds,rms,max,"
           "rms_vs_uniform_ref,max_vs_uniform_ref,unlocated\n";
    for (const AccuracyCase& c : cases) {
        const SceneInput input = c.scene.arrays.input();
        const Samples samples = sample_polygons(input, c.sample_spacing);
        std::size_t unlocated = 0;
        auto colours = [&](const Baked& b) { return colours_at(samples, b.mesh, b.corners, unlocated); };
        // Two references by different methods, each finer than any run's links: the hierarchy at
        // a quarter of the default tolerance and the uniform mesh at a fine hemi-cube resolution,
        // both solved tightly. Each stands for the light without the lamps' first reflection;
        // that is taken exactly at every sample (reference_colours), for both alike.
        const HierarchyReference h_ref = hierarchy_reference(c, input, samples);
        const std::vector<Rgb>& h_colours = h_ref.colours;
        std::size_t u_unlocated = 0;
        const Baked u_ref = bake_uniform(c.scene, c.reference_size, c.reference_resolution, 1e-6);
        const auto u_colours =
            reference_colours(samples, u_ref.mesh, u_ref.radiance, input.material, h_ref.lamp, u_unlocated);
        auto row = [&](const std::string& method, double parameter, float min_size, int lamp_levels, const Baked& b,
                       const std::vector<Rgb>& got) {
            const ColourError e = colour_error(samples, got, h_colours);
            const ColourError eu = colour_error(samples, got, u_colours);
            csv << c.name << "," << method << "," << parameter << "," << min_size << "," << lamp_levels << ","
                << b.elements << "," << b.output_elements << "," << b.links << "," << b.seconds << "," << e.rms << ","
                << e.max << "," << eu.rms << "," << eu.max << "," << unlocated << "\n"
                << std::flush;
            std::printf(
                "%-12s %-20s %8.4g elements %8zu output %8zu  %7.2f s  rms %.4f max %.3f  (vs uniform ref: rms "
                "%.4f max %.3f)  unlocated %zu\n",
                c.name.c_str(), method.c_str(), parameter, b.elements, b.output_elements, b.seconds, e.rms, e.max,
                eu.rms, eu.max, unlocated);
            std::fflush(stdout);
        };
        std::printf("%s: %zu samples\n", c.name.c_str(), samples.point.size());
        unlocated = u_unlocated;
        row("reference_uniform", c.reference_size, c.reference_size, 0, u_ref, u_colours);
        unlocated = h_ref.unlocated;
        row("reference_hierarchy", 0.005, c.reference_size, 0, h_ref.baked, h_colours);
        for (float size : c.sizes) {
            const Baked b = bake_uniform(c.scene, size, 128, 1e-4);
            row("uniform", size, size, 0, b, colours(b));
        }
        for (const HierarchySeries& series : c.series)
            for (double t : c.refine_tolerances) {
                const Baked b = bake_hierarchy(c.scene, series.min_size, series.lamp_levels, t, 1e-4, 12);
                row(series.method, t, series.min_size, series.lamp_levels, b, colours(b));
            }
    }
}

}  // namespace radiosity::charts
