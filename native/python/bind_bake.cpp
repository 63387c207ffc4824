/// @file bind_bake.cpp
/// @brief `_core.bake` (flat numpy arrays in, corner colours and statistics out) and `_core.elements`.
#include "arrays.h"
#include "bindings.h"
#include "progress.h"
#include "progress_monitor.h"
#include "scene_arrays.h"

#include "radiosity/bake.h"

#include <pybind11/stl.h>

namespace radiosity::python {

namespace {

Method parse_method(const std::string& name) {
    if (name == "gauss_seidel") return Method::GaussSeidel;
    if (name == "jacobi") return Method::Jacobi;
    if (name == "progressive") return Method::Progressive;
    throw py::value_error("method must be 'gauss_seidel', 'jacobi' or 'progressive', got '" + name + "'");
}

/// Element corner colours as (E, 4, 3); the 4th corner of a triangle repeats zero.
py::array_t<float> element_corner_array(const std::vector<Rgb>& element_corner) {
    const auto count = static_cast<py::ssize_t>(element_corner.size() / 4);
    py::array_t<float> out({count, py::ssize_t{4}, py::ssize_t{3}});
    float* o = out.mutable_data();
    for (std::size_t k = 0; k < element_corner.size(); ++k)
        for (int c = 0; c < 3; ++c) o[3 * k + c] = static_cast<float>(element_corner[k][c]);
    return out;
}

py::dict bake_arrays(const Array<float>& positions, const Array<int32_t>& face_offsets,
                     const Array<int32_t>& corner_vertices, const Array<float>& reflectance,
                     const Array<float>& emission, const std::optional<Array<int32_t>>& material,
                     float element_size, int resolution, const std::string& method, double tolerance,
                     int max_iterations, float hard_edge_angle, bool ambient, const py::list& lights,
                     std::size_t matrix_budget_bytes,
                     const py::object& progress) {
    const SceneInput input = scene_input(positions, face_offsets, corner_vertices, reflectance, emission, material);
    if (resolution < 8 || resolution % 2 != 0) throw py::value_error("resolution must be an even number >= 8");
    if (!(element_size >= 0.0f)) throw py::value_error("element_size must be >= 0");
    if (!(tolerance > 0.0)) throw py::value_error("tolerance must be > 0");
    if (max_iterations < 1) throw py::value_error("max_iterations must be >= 1");

    BakeSettings settings;
    settings.element_size = element_size;
    settings.resolution = resolution;
    settings.solve.method = parse_method(method);
    settings.solve.tolerance = tolerance;
    settings.solve.max_iterations = max_iterations;
    settings.solve.ambient = ambient;
    settings.hard_edge_angle = hard_edge_angle;
    settings.lights = parse_lights(lights);
    settings.matrix_budget_bytes = matrix_budget_bytes;

    // A ProgressMonitor reports without the GIL; anything else is called as a Python callback.
    auto* monitor = py::isinstance<ProgressMonitor>(progress) ? progress.cast<ProgressMonitor*>() : nullptr;
    ProgressBridge bridge(monitor ? py::none() : progress);
    const ProgressFn report = monitor ? monitor->function() : bridge.function();
    BakeResult result;
    try {
        py::gil_scoped_release release;
        result = bake(input, settings, report);
    } catch (const Cancelled&) {
        bridge.rethrow_if_failed();
        throw;
    }

    py::dict seconds;
    seconds["elements"] = result.seconds_elements;
    seconds["lights"] = result.seconds_lights;
    seconds["form_factors"] = result.seconds_form_factors;
    seconds["solve"] = result.seconds_solve;
    seconds["interpolate"] = result.seconds_interpolate;

    py::dict out;
    add_elements(result.build, out);
    out["corner_radiance"] = to_numpy(result.colors.input_corner);
    out["element_corner_radiance"] = element_corner_array(result.colors.element_corner);
    out["element_radiance"] = to_numpy(result.solve.radiance);
    out["iterations"] = result.solve.iterations;
    out["shots"] = result.solve.shots;
    out["residual"] = result.solve.residual;
    out["residual_history"] = result.solve.residual_history;
    out["converged"] = result.solve.converged;
    out["matrix_stored"] = result.matrix_stored;
    out["matrix_nonzeros"] = result.matrix_nonzeros;
    out["matrix_bytes"] = result.matrix_bytes;
    out["seconds"] = seconds;
    // What the solve used per element, so the add-on can account for power: emission includes
    // the lamps' first reflection (rho E / pi), reflectance is the capped input.
    out["element_emission"] = to_numpy(result.build.elements.emission);
    out["element_reflectance"] = to_numpy(result.build.elements.reflectance);
    return out;
}

py::dict element_arrays(const Array<float>& positions, const Array<int32_t>& face_offsets,
                        const Array<int32_t>& corner_vertices, const Array<float>& reflectance,
                        const Array<float>& emission, const std::optional<Array<int32_t>>& material,
                        float element_size) {
    const SceneInput input = scene_input(positions, face_offsets, corner_vertices, reflectance, emission, material);
    if (!(element_size >= 0.0f)) throw py::value_error("element_size must be >= 0");
    BuildResult build;
    {
        py::gil_scoped_release release;
        build = build_elements(input, element_size);
    }
    py::dict out;
    add_elements(build, out);
    return out;
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
          "progress"_a = py::none());
    m.def("elements", &element_arrays,
          "The elements bake() would solve for (same order as its progress radiance), without solving.",
          "positions"_a, "face_offsets"_a, "corner_vertices"_a, "reflectance"_a, "emission"_a,
          "material"_a = py::none(), py::kw_only(), "element_size"_a = 0.0f);
    // The core's own memory model, so the add-on's automatic method agrees with bake()'s choice.
    m.def("matrix_bytes_bound", &matrix_bytes_bound,
          "Upper bound of the stored form-factor matrix's bytes for n elements at hemi-cube resolution N.",
          "element_count"_a, "resolution"_a);
    m.attr("DEFAULT_MATRIX_BUDGET_BYTES") = BakeSettings().matrix_budget_bytes;
}

}  // namespace radiosity::python
