/// @file bind_bake.cpp
/// @brief `_core.plan` and `_core.bake` (flat numpy arrays and keyword settings in; elements, or corner
/// colours and statistics, out) and the core's memory and resolution models.
#include "arrays.h"
#include "bake_keywords.h"
#include "bindings.h"
#include "layer_arrays.h"
#include "scene_arrays.h"
#include "texture_arrays.h"

#include "bake/bake.h"
#include "bake/bake_cache.h"
#include "visibility/resolution.h"

#include <pybind11/stl.h>

namespace radiosity::python {

namespace {

/// The scene `_core.plan` and `_core.bake` take: the arrays viewed as a SceneInput, with the
/// textures it points into kept beside it (so it is neither copied nor moved).
class TexturedScene {
public:
    TexturedScene(const Array<float>& positions, const Array<int32_t>& face_offsets,
                  const Array<int32_t>& corner_vertices, const Array<float>& reflectance, const Array<float>& emission,
                  const std::optional<Array<int32_t>>& material, const std::optional<Array<uint8_t>>& front_only,
                  const py::object& textures)
        : input(scene_input(positions, face_offsets, corner_vertices, reflectance, emission, material, front_only)),
          textures_(parse_textures(textures, face_offsets.shape(0) - 1, corner_vertices.shape(0))) {
        if (textures_) input.textures = &textures_->view;
    }
    TexturedScene(const TexturedScene&) = delete;
    TexturedScene& operator=(const TexturedScene&) = delete;

    SceneInput input;

private:
    std::optional<TextureArrays> textures_;
};

py::dict bake_arrays(const Array<float>& positions, const Array<int32_t>& face_offsets,
                     const Array<int32_t>& corner_vertices, const Array<float>& reflectance,
                     const Array<float>& emission, const std::optional<Array<int32_t>>& material,
                     const std::optional<Array<uint8_t>>& front_only, const py::object& textures,
                     const py::object& progress, const py::kwargs& keywords) {
    const TexturedScene scene(positions, face_offsets, corner_vertices, reflectance, emission, material, front_only,
                              textures);
    py::kwargs settings_keywords;
    for (const auto& item : keywords) {
        const std::string name = py::str(item.first).cast<std::string>();
        if (name != "layers" && name != "cache") settings_keywords[item.first] = item.second;
    }
    BakeCache* cache =
        keywords.contains("cache") && !keywords["cache"].is_none() ? keywords["cache"].cast<BakeCache*>() : nullptr;
    const BakeSettings settings = bake_settings(settings_keywords);
    std::optional<LayerSources> layers;
    if (keywords.contains("layers") && !keywords["layers"].is_none())
        layers = parse_layers(
            keywords["layers"].cast<py::dict>(), scene.input.face_count,
            settings_keywords.contains("lights") ? settings_keywords["lights"].cast<py::list>() : py::list());
    ProgressReporter reporter(progress);
    BakeResult result;
    LayeredBake layered;
    try {
        py::gil_scoped_release release;
        if (layers)
            layered = bake_layers(scene.input, settings, *layers, reporter.function(), cache);
        else
            result = bake(scene.input, settings, reporter.function(), cache);
    } catch (const Cancelled&) {
        reporter.rethrow_if_failed();
        throw;
    }
    return layers ? layered_result(layered) : bake_result(result);
}

py::dict plan_arrays(const Array<float>& positions, const Array<int32_t>& face_offsets,
                     const Array<int32_t>& corner_vertices, const Array<float>& reflectance,
                     const Array<float>& emission, const std::optional<Array<int32_t>>& material,
                     const std::optional<Array<uint8_t>>& front_only, const py::object& textures,
                     const py::kwargs& keywords) {
    const TexturedScene scene(positions, face_offsets, corner_vertices, reflectance, emission, material, front_only,
                              textures);
    const BakeSettings settings = bake_settings(keywords);
    BakePlan planned;
    {
        py::gil_scoped_release release;
        planned = plan(scene.input, settings);
    }
    py::dict out;
    add_elements(planned.build, out);
    out["solve_elements"] = planned.solve_elements;
    out["solve_element_area"] = to_numpy(planned.solve_element_area);
    out["solve_element_polygon"] = to_numpy(planned.solve_element_polygon);
    out["matrix_bytes_bound"] = planned.matrix_bytes_bound;
    out["matrix_bytes_planned"] = planned.matrix_bytes_planned;
    out["matrix_stored"] = planned.matrix_stored;
    out["sight_distance"] = planned.sight_distance;
    out["resolution_distance"] = planned.resolution_distance;
    return out;
}

int recommended_resolution_arrays(const Array<float>& element_area, double distance, double cells) {
    require_shape(element_area, "element_area", -1, 0);
    if (!(cells > 0.0)) throw InputError("cells must be > 0");
    if (!(distance >= 0.0)) throw InputError("distance must be >= 0");
    const float* area = element_area.data();
    return recommended_resolution(std::vector<float>(area, area + element_area.shape(0)), distance, cells);
}

double resolved_area_arrays(double distance, int resolution, double cells) {
    if (!(cells > 0.0)) throw InputError("cells must be > 0");
    if (resolution < 1) throw InputError("resolution must be >= 1");
    if (!(distance >= 0.0)) throw InputError("distance must be >= 0");
    return resolved_area(distance, resolution, cells);
}

}  // namespace

void bind_bake(py::module_& m) {
    using namespace pybind11::literals;
    py::class_<BakeCache>(m, "BakeCache",
                          "What a uniform bake learned about the geometry (elements, form factors, the final gather's "
                          "rays' hits), kept for the next bake of the same geometry: bake(..., cache=c) reads it when "
                          "the geometry matches and leaves its own in it (the result's cache says which). Opaque; "
                          "one bake at a time.")
        .def(py::init<>())
        .def_property_readonly("bytes", &BakeCache::bytes, "The bytes it holds; 0 when empty.")
        .def_property_readonly("empty", &BakeCache::empty)
        .def("clear", &BakeCache::clear, "Lets go of what it holds.");
    m.def("bake", &bake_arrays,
          "Bakes radiosity for a polygon soup given as flat arrays (see the add-on's export for the layout) by the "
          "pipeline the settings choose, and returns one dict whatever the method. The scene may carry textures "
          "(texture_arrays.h) besides front_only. Settings, all keywords: "
          "element_size (the longest edge of the finest elements, metres; 0: one element per polygon, uniform "
          "methods only), method ('gauss_seidel', 'jacobi', 'progressive' or 'hierarchical'), resolution (hemi-cube "
          "cells per face edge, even), tolerance, max_iterations, hard_edge_angle, ambient, lights (list of dicts), "
          "world (None or an equirectangular (h, w, 3) map), world_samples, world_point_samples, "
          "matrix_budget_bytes; the stability settings near_field, over_relaxation (0: the core's), "
          "max_element_aspect, max_elements, hemicube_rotations, direct_emitter_area, merge_elements (uniform "
          "methods: small coplanar elements merge into solve elements of up to element_size; default True); the "
          "final gather: "
          "final_gather, gather_rays, gather_shadow_rays, gather_field_rays, gather_cache_accuracy (irradiance caching "
          "between output corners, Ward's a; 0: every corner gathers); the hierarchy: refine_tolerance, max_bytes; "
          "media: media "
          "([{origin, voxel_size, extinction, albedo, emission (nz, ny, nx, 3)}]), zone_resolution, "
          "grid_subdivision, merge_uniform_zones; cache (a BakeCache: the uniform methods reuse the elements, form "
          "factors and gather's hits of its previous bake when the geometry matches, and keep theirs; the dict then "
          "adds cache {reused, merged_again, kept, bytes, direct_bytes, not_reused, not_kept}); light group layers: "
          "layers ({count, "
          "polygon: a "
          "layer per polygon, "
          "lamp: a layer per lights entry, world: its layer}, uniform methods only; the dict then adds layers, per "
          "layer corner_radiance, element_corner_radiance, corner_light, element_corner_light, element_radiance, "
          "element_emission, iterations, residual, converged, seconds, and the rest is their sum). The dict: the "
          "elements (as plan() gives them; the hierarchy's leaves), corner_radiance, element_corner_radiance, "
          "element_radiance, element_emission, "
          "element_reflectance, corner_light and element_corner_light, iterations, shots, residual, "
          "residual_history, converged, solve_elements (the unknowns solved), matrix_stored, matrix_nonzeros, "
          "matrix_bytes, seconds per phase, "
          "final_gather (points gathered, interpolated, buried, phases {field, wedges, probes, points, seams, other: "
          "{seconds, rays}} and what the error estimate reads: solution_light, indirect, variance, "
          "field_noise per corner, element_field_error and element_reflected per element) and direct_emitters when "
          "they ran, hierarchy (its counts, or None), and with media zones, "
          "zones_before_merge, zone_radiance, zone_medium, zone_weight (4 K_t V), zone_emitted, zone_albedo, "
          "zone_incident and per medium grids [{origin, voxel_size, density: K_t, emission: K_t J}].",
          "positions"_a, "face_offsets"_a, "corner_vertices"_a, "reflectance"_a, "emission"_a,
          "material"_a = py::none(), py::kw_only(), "front_only"_a = py::none(), "textures"_a = py::none(),
          "progress"_a = py::none());
    m.def("plan", &plan_arrays,
          "What bake() with the same arrays and settings will solve, without solving: its elements (element_vertices, "
          "element_corners, element_polygon, element_area, elements, skipped; in the order of its progress radiance; "
          "the hierarchy's patches), solve_elements, solve_element_area and solve_element_polygon (the unknowns, "
          "their areas and input polygons: fewer than the elements where small ones merge), "
          "matrix_bytes_bound, matrix_bytes_planned (uniform methods: the bound when it fits matrix_budget_bytes, "
          "else the bytes estimated from a sample of the matrix's rows at the settings' resolution, with a margin of "
          "3 standard errors), matrix_stored (the planned bytes fit the budget: the form factors are stored, else "
          "rendered on demand), sight_distance (the power mean of the hit distances of cosine-weighted rays from "
          "area-stratified points) and resolution_distance (the distance the resolution is judged from: "
          "1.9 x sight_distance, at most half the diagonal of the elements' bounding box). Takes bake()'s settings.",
          "positions"_a, "face_offsets"_a, "corner_vertices"_a, "reflectance"_a, "emission"_a,
          "material"_a = py::none(), py::kw_only(), "front_only"_a = py::none(), "textures"_a = py::none());
    // The core's own memory model, so the add-on's automatic method agrees with bake()'s choice.
    m.def("matrix_bytes_bound", &matrix_bytes_bound,
          "Upper bound of the stored form-factor matrix's bytes for n elements at hemi-cube resolution N.",
          "element_count"_a, "resolution"_a);
    m.def("layer_bytes_bound", &layer_bytes_bound,
          "Upper bound of the bytes `layers` light group layers add to a bake of `elements` elements and `corners` "
          "input corners (the core's; the add-on checks it against the memory budget).",
          "layers"_a, "elements"_a, "corners"_a);
    m.def("recommended_resolution", &recommended_resolution_arrays,
          "Even hemi-cube resolution in [32, 1024] at which the smallest elements holding a tenth of element_area's "
          "total, seen head-on from `distance` (plan()'s resolution_distance), cover `cells` cells: 2 d sqrt(cells / "
          "A).",
          "element_area"_a, "distance"_a, "cells"_a = 8.0);
    m.def("resolved_area", &resolved_area_arrays,
          "The area an element must have to cover `cells` cells of a hemi-cube of `resolution`, seen head-on from "
          "`distance` (plan()'s resolution_distance): cells (2 d / N)^2 (recommended_resolution inverted).",
          "distance"_a, "resolution"_a, "cells"_a);
    m.attr("DEFAULT_MATRIX_BUDGET_BYTES") = BakeSettings().matrix_budget_bytes;
}

}  // namespace radiosity::python
