#include "hierarchy_accuracy.h"

#include "charts.h"
#include "hierarchy_error.h"
#include "hierarchy_scenes.h"
#include "radiosity/bake.h"
#include "radiosity/hierarchy.h"

#include <cstdio>
#include <fstream>

namespace radiosity::charts {
namespace {

/// One scene's runs: uniform element sizes (the last is the finest) and refine tolerances.
struct AccuracyCase {
    std::string name;
    LitScene scene;
    std::vector<float> sizes;
    std::vector<double> refine_tolerances;
    float sample_spacing;
};

/// A bake's mesh and corner colours, how big it is and how long it took.
struct Baked {
    Elements mesh;
    std::vector<Rgb> corners;
    std::size_t elements = 0, output_elements = 0, links = 0;
    double seconds = 0.0;
};

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
    b.corners = std::move(r.colors.element_corner);
    return b;
}

Baked bake_hierarchy(const LitScene& scene, float min_size, double refine_tolerance, double tolerance, int rounds) {
    HierarchySettings s;
    s.min_element_size = min_size;
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
    b.corners = std::move(r.colors.element_corner);
    return b;
}

}  // namespace

void accuracy(const std::string& csv_path) {
    std::vector<AccuracyCase> cases;
    cases.push_back({"cornell", {test::cornell_box(), {}, 0.0f}, {0.2f, 0.1f, 0.07f, 0.05f},
                     {0.2, 0.1, 0.05, 0.02, 0.01}, 0.004f});
    cases.push_back({"shadow_room", shadow_room(), {0.4f, 0.2f, 0.14f, 0.1f},
                     {0.2, 0.1, 0.05, 0.02, 0.01}, 0.01f});
    std::ofstream csv(csv_path);
    csv << "scene,method,parameter,elements,output_elements,links,seconds,rms,max,rms_vs_uniform_ref,"
           "max_vs_uniform_ref,unlocated\n";
    for (const AccuracyCase& c : cases) {
        const Samples samples = sample_polygons(c.scene.arrays.input(), c.sample_spacing);
        std::size_t unlocated = 0;
        auto colours = [&](const Baked& b) { return colours_at(samples, b.mesh, b.corners, unlocated); };
        // Two references by different methods, each finer than any measured run: the hierarchy
        // at a quarter of the default tolerance down to half the finest uniform size, and the
        // uniform mesh at half the finest size and hemi-cube resolution 256; both solved tightly.
        const float finest = c.sizes.back();
        const Baked h_ref = bake_hierarchy(c.scene, finest / 2, 0.005, 1e-6, 12);
        const auto h_colours = colours(h_ref);
        const std::size_t h_unlocated = unlocated;
        const Baked u_ref = bake_uniform(c.scene, finest / 2, 256, 1e-6);
        const auto u_colours = colours(u_ref);
        auto row = [&](const std::string& method, double parameter, const Baked& b, const std::vector<Rgb>& got) {
            const ColourError e = colour_error(samples, got, h_colours);
            const ColourError eu = colour_error(samples, got, u_colours);
            csv << c.name << "," << method << "," << parameter << "," << b.elements << "," << b.output_elements << ","
                << b.links << "," << b.seconds << "," << e.rms << "," << e.max << "," << eu.rms << "," << eu.max << ","
                << unlocated << "\n" << std::flush;
            std::printf("%-12s %-20s %8.4g elements %8zu output %8zu  %7.2f s  rms %.4f max %.3f  (vs uniform ref: rms "
                        "%.4f max %.3f)  unlocated %zu\n",
                        c.name.c_str(), method.c_str(), parameter, b.elements, b.output_elements, b.seconds, e.rms,
                        e.max, eu.rms, eu.max, unlocated);
            std::fflush(stdout);
        };
        std::printf("%s: %zu samples, hierarchy reference unlocated %zu\n", c.name.c_str(), samples.point.size(),
                    h_unlocated);
        row("reference_uniform", finest / 2, u_ref, u_colours);
        unlocated = h_unlocated;
        row("reference_hierarchy", 0.005, h_ref, h_colours);
        for (float size : c.sizes) {
            const Baked b = bake_uniform(c.scene, size, 128, 1e-4);
            row("uniform", size, b, colours(b));
        }
        for (double t : c.refine_tolerances) {
            const Baked b = bake_hierarchy(c.scene, finest, t, 1e-4, 12);
            row("hierarchy", t, b, colours(b));
        }
    }
}

}  // namespace radiosity::charts
