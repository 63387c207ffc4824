/// @file bind_bake.cpp
/// @brief `_core.bake` (flat numpy arrays in, corner colours and statistics out) and `_core.elements`.
#include "arrays.h"
#include "bake_keywords.h"
#include "bindings.h"
#include "scene_arrays.h"
#include "texture_arrays.h"

#include "radiosity/bake.h"
#include "radiosity/resolution.h"

#include <pybind11/stl.h>

namespace radiosity::python {

namespace {

py::dict bake_arrays(const Array<float>& positions, const Array<int32_t>& face_offsets,
                     const Array<int32_t>& corner_vertices, const Array<float>& reflectance,
                     const Array<float>& emission, const std::optional<Array<int32_t>>& material,
                     float element_size, int resolution, const std::string& method, double tolerance,
                     int max_iterations, float hard_edge_angle, bool ambient, const py::list& lights,
                     std::size_t matrix_budget_bytes,
                     const py::object& progress, bool near_field, double over_relaxation, float max_element_aspect,
                     std::size_t max_elements, int hemicube_rotations, bool final_gather, int gather_rays,
                     int gather_shadow_rays, float direct_emitter_area, const py::object& world, int world_samples,
                     int world_point_samples, const std::optional<Array<uint8_t>>& front_only,
                     const py::object& textures) {
    SceneInput input = scene_input(positions, face_offsets, corner_vertices, reflectance, emission, material, front_only);
    const std::optional<TextureArrays> texture_arrays =
        parse_textures(textures, face_offsets.shape(0) - 1, corner_vertices.shape(0));
    if (texture_arrays) input.textures = &texture_arrays->view;
    BakeSettings settings = bake_settings(element_size, resolution, method, tolerance, max_iterations,
                                          hard_edge_angle, ambient, lights, matrix_budget_bytes);
    // The stability settings of docs/stability.md; the core checks their ranges (ValueError).
    settings.near_field.enabled = near_field;
    settings.solve.over_relaxation = over_relaxation;
    settings.limits.max_aspect = max_element_aspect;
    settings.limits.max_elements = max_elements;
    settings.hemicube_rotations = hemicube_rotations;
    if (gather_rays < 1) throw InputError("gather_rays must be >= 1");
    if (gather_shadow_rays < 1) throw InputError("gather_shadow_rays must be >= 1");
    settings.final_gather.enabled = final_gather;
    settings.final_gather.rays = gather_rays;
    settings.final_gather.shadow_rays = gather_shadow_rays;
    if (!(direct_emitter_area >= 0.0f)) throw InputError("direct_emitter_area must be >= 0");
    settings.direct_emitter_area = direct_emitter_area;
    settings.world = parse_world(world, world_samples, world_point_samples);
    ProgressReporter reporter(progress);
    BakeResult result;
    try {
        py::gil_scoped_release release;
        result = bake(input, settings, reporter.function());
    } catch (const Cancelled&) {
        reporter.rethrow_if_failed();
        throw;
    }
    py::dict out;
    add_bake_result(result, out);
    return out;
}

py::dict element_arrays(const Array<float>& positions, const Array<int32_t>& face_offsets,
                        const Array<int32_t>& corner_vertices, const Array<float>& reflectance,
                        const Array<float>& emission, const std::optional<Array<int32_t>>& material,
                        float element_size, float max_element_aspect, const std::optional<Array<uint8_t>>& front_only,
                        const py::object& textures) {
    SceneInput input = scene_input(positions, face_offsets, corner_vertices, reflectance, emission, material, front_only);
    const std::optional<TextureArrays> texture_arrays =
        parse_textures(textures, face_offsets.shape(0) - 1, corner_vertices.shape(0));
    if (texture_arrays) input.textures = &texture_arrays->view;
    if (!(element_size >= 0.0f)) throw InputError("element_size must be >= 0");
    BuildResult build;
    {
        py::gil_scoped_release release;
        ElementLimits limits = BakeSettings().limits;  // with bake()'s contact cuts: the same mesh
        limits.max_aspect = max_element_aspect;
        build = build_elements(input, element_size, limits);
    }
    py::dict out;
    add_elements(build, out);
    return out;
}

/// Elements with only their vertices: recommended_resolution and resolved_area read the areas (none
/// here), the count (size() is centre.size()) and the vertices' bounding box.
Elements vertex_layout(const Array<float>& element_vertices) {
    require_shape(element_vertices, "element_vertices", -1, 3);
    Elements elements;
    const float* v = element_vertices.data();
    for (py::ssize_t i = 0; i < element_vertices.shape(0); ++i)
        elements.vertices.emplace_back(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
    return elements;
}

int recommended_resolution_arrays(const Array<float>& element_area, const Array<float>& element_vertices,
                                  double cells) {
    require_shape(element_area, "element_area", -1, 0);
    if (!(cells > 0.0)) throw InputError("cells must be > 0");
    Elements elements = vertex_layout(element_vertices);
    const float* area = element_area.data();
    elements.area.assign(area, area + element_area.shape(0));
    elements.centre.resize(elements.area.size());
    return recommended_resolution(elements, cells);
}

double resolved_area_arrays(const Array<float>& element_vertices, int resolution, double cells) {
    if (!(cells > 0.0)) throw InputError("cells must be > 0");
    if (resolution < 1) throw InputError("resolution must be >= 1");
    return resolved_area(vertex_layout(element_vertices), resolution, cells);
}

}  // namespace

void bind_bake(py::module_& m) {
    using namespace pybind11::literals;
    m.def("bake", &bake_arrays,
          "Bakes radiosity for a polygon soup given as flat arrays; see the add-on's export for the layout.",
          "positions"_a, "face_offsets"_a, "corner_vertices"_a, "reflectance"_a, "emission"_a,
          "material"_a = py::none(), py::kw_only(), "element_size"_a = 0.0f, "resolution"_a = 128,
          "method"_a = "gauss_seidel", "tolerance"_a = 1e-4, "max_iterations"_a = 1000,
          "hard_edge_angle"_a = 0.5235988f, "ambient"_a = false, "lights"_a = py::list(),
          "matrix_budget_bytes"_a = BakeSettings().matrix_budget_bytes,
          "progress"_a = py::none(), "near_field"_a = false, "over_relaxation"_a = 1.0,
          "max_element_aspect"_a = 0.0f, "max_elements"_a = ElementLimits().max_elements, "hemicube_rotations"_a = 1,
          "final_gather"_a = false, "gather_rays"_a = FinalGatherSettings().rays,
          "gather_shadow_rays"_a = FinalGatherSettings().shadow_rays,
          "direct_emitter_area"_a = BakeSettings().direct_emitter_area, "world"_a = py::none(),
          "world_samples"_a = WorldLight().samples, "world_point_samples"_a = WorldLight().point_samples,
          "front_only"_a = py::none(), "textures"_a = py::none());
    m.def("elements", &element_arrays,
          "The elements bake() would solve for (same order as its progress radiance), without solving.",
          "positions"_a, "face_offsets"_a, "corner_vertices"_a, "reflectance"_a, "emission"_a,
          "material"_a = py::none(), py::kw_only(), "element_size"_a = 0.0f, "max_element_aspect"_a = 0.0f,
          "front_only"_a = py::none(), "textures"_a = py::none());
    // The core's own memory model, so the add-on's automatic method agrees with bake()'s choice.
    m.def("matrix_bytes_bound", &matrix_bytes_bound,
          "Upper bound of the stored form-factor matrix's bytes for n elements at hemi-cube resolution N.",
          "element_count"_a, "resolution"_a);
    m.def("recommended_resolution", &recommended_resolution_arrays,
          "Even hemi-cube resolution in [32, 1024] at which the 10th percentile of element_area, seen head-on "
          "from half the diagonal of element_vertices' bounding box, covers `cells` cells: 2 d sqrt(cells / A).",
          "element_area"_a, "element_vertices"_a, "cells"_a = 8.0);
    m.def("resolved_area", &resolved_area_arrays,
          "The area an element must have to cover `cells` cells of a hemi-cube of `resolution`, seen head-on from "
          "half the diagonal of element_vertices' bounding box: cells (2 d / N)^2 (recommended_resolution inverted).",
          "element_vertices"_a, "resolution"_a, "cells"_a);
    m.attr("DEFAULT_MATRIX_BUDGET_BYTES") = BakeSettings().matrix_budget_bytes;
}

}  // namespace radiosity::python
