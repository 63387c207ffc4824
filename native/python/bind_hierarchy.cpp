/// @file bind_hierarchy.cpp
/// @brief `_core.bake_hierarchical`: the hierarchical bake, with bake()'s result keys (the
/// leaves as elements) plus its own counts under "hierarchy".
#include "arrays.h"
#include "bake_keywords.h"
#include "bindings.h"
#include "scene_arrays.h"

#include "hierarchy/hierarchy.h"

#include <pybind11/stl.h>

namespace radiosity::python {

namespace {

py::dict hierarchy_counts(const HierarchyStats& stats) {
    py::dict out;
    out["patches"] = stats.patches;
    out["clusters"] = stats.clusters;
    out["leaves"] = stats.leaves;
    out["lamp_splits"] = stats.lamp_splits;
    out["nodes"] = stats.nodes;
    out["links"] = stats.links;
    out["rays"] = stats.rays;
    out["bytes"] = stats.bytes;
    out["rounds"] = stats.rounds;
    out["leaf_cap_reached"] = stats.leaf_cap_reached;
    out["memory_cap_reached"] = stats.memory_cap_reached;
    return out;
}

py::dict bake_hierarchical_arrays(const Array<float>& positions, const Array<int32_t>& face_offsets,
                                  const Array<int32_t>& corner_vertices, const Array<float>& reflectance,
                                  const Array<float>& emission, const std::optional<Array<int32_t>>& material,
                                  float element_size, double refine_tolerance, double tolerance, int max_iterations,
                                  float hard_edge_angle, const py::list& lights, std::size_t max_elements,
                                  std::size_t max_bytes, const py::object& progress, const py::object& world,
                                  int world_samples, int world_point_samples,
                                  const std::optional<Array<uint8_t>>& front_only) {
    const SceneInput input =
        scene_input(positions, face_offsets, corner_vertices, reflectance, emission, material, front_only);
    HierarchySettings settings;
    settings.min_element_size = element_size;
    settings.refine_tolerance = refine_tolerance;
    settings.tolerance = tolerance;
    settings.max_iterations = max_iterations;
    settings.hard_edge_angle = hard_edge_angle;
    settings.lights = parse_lights(lights);
    settings.limits.max_elements = max_elements;
    settings.max_bytes = max_bytes;
    settings.world = parse_world(world, world_samples, world_point_samples);
    ProgressReporter reporter(progress);
    HierarchyResult result;
    try {
        py::gil_scoped_release release;
        result = bake_hierarchical(input, settings, reporter.function());
    } catch (const Cancelled&) {
        reporter.rethrow_if_failed();
        throw;
    }
    // The output mesh stands where bake() puts its elements; the patches' skipped list stays.
    BuildResult leaves{std::move(result.output), std::move(result.build.skipped)};
    py::dict out;
    add_elements(leaves, out);
    add_surface_solution(leaves.elements, result.output_radiance, result.colors, out);
    py::dict seconds;
    seconds["elements"] = result.seconds_elements;
    seconds["lights"] = 0.0;  // lamps are link sources: their light is part of the links
    seconds["form_factors"] = result.seconds_links;
    seconds["solve"] = result.seconds_solve;
    seconds["interpolate"] = result.seconds_interpolate;
    out["seconds"] = seconds;
    out["iterations"] = result.stats.iterations;
    out["shots"] = 0;
    out["residual"] = result.residual;
    out["residual_history"] = result.residual_history;
    out["converged"] = result.converged;
    out["matrix_stored"] = false;
    out["matrix_nonzeros"] = 0;
    out["matrix_bytes"] = result.stats.bytes;
    out["hierarchy"] = hierarchy_counts(result.stats);
    return out;
}

}  // namespace

void bind_hierarchy(py::module_& m) {
    using namespace pybind11::literals;
    m.def("bake_hierarchical", &bake_hierarchical_arrays,
          "Bakes hierarchically (elements refined where the light needs them, clusters linked far off). "
          "element_size is the finest element edge in metres; refine_tolerance the error allowed per link "
          "as a share of the scene's mean reflected radiance; max_bytes caps its nodes and links (0: no cap).",
          "positions"_a, "face_offsets"_a, "corner_vertices"_a, "reflectance"_a, "emission"_a,
          "material"_a = py::none(), py::kw_only(), "element_size"_a = HierarchySettings().min_element_size,
          "refine_tolerance"_a = HierarchySettings().refine_tolerance, "tolerance"_a = 1e-4,
          "max_iterations"_a = 1000, "hard_edge_angle"_a = 0.5235988f, "lights"_a = py::list(),
          "max_elements"_a = ElementLimits().max_elements, "max_bytes"_a = 0, "progress"_a = py::none(),
          "world"_a = py::none(), "world_samples"_a = WorldLight().samples,
          "world_point_samples"_a = WorldLight().point_samples, "front_only"_a = py::none());
}

}  // namespace radiosity::python
