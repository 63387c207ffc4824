/// @file bake_keywords.cpp
/// @brief Settings, progress and result conversion shared by the bake entry points.
#include "bake_keywords.h"

#include "arrays.h"
#include "bindings.h"
#include "scene_arrays.h"

#include <pybind11/stl.h>

namespace radiosity::python {

namespace {

Method parse_method(const std::string& name) {
    if (name == "gauss_seidel") return Method::GaussSeidel;
    if (name == "jacobi") return Method::Jacobi;
    if (name == "progressive") return Method::Progressive;
    throw InputError("method must be 'gauss_seidel', 'jacobi' or 'progressive', got '" + name + "'");
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

ProgressMonitor* monitor_of(const py::object& progress) {
    return py::isinstance<ProgressMonitor>(progress) ? progress.cast<ProgressMonitor*>() : nullptr;
}

}  // namespace

BakeSettings bake_settings(float element_size, int resolution, const std::string& method, double tolerance,
                           int max_iterations, float hard_edge_angle, bool ambient, const py::list& lights,
                           std::size_t matrix_budget_bytes) {
    if (resolution < 8 || resolution % 2 != 0) throw InputError("resolution must be an even number >= 8");
    if (!(element_size >= 0.0f)) throw InputError("element_size must be >= 0");
    if (!(tolerance > 0.0)) throw InputError("tolerance must be > 0");
    if (max_iterations < 1) throw InputError("max_iterations must be >= 1");
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
    return settings;
}

ProgressReporter::ProgressReporter(const py::object& progress)
    : monitor_(monitor_of(progress)), bridge_(monitor_ ? py::none() : progress),
      function_(monitor_ ? monitor_->function() : bridge_.function()) {}

void add_bake_result(const BakeResult& result, py::dict& out) {
    py::dict seconds;
    seconds["elements"] = result.seconds_elements;
    seconds["lights"] = result.seconds_lights;
    seconds["world"] = result.seconds_world;
    seconds["form_factors"] = result.seconds_form_factors;
    seconds["solve"] = result.seconds_solve;
    seconds["interpolate"] = result.seconds_interpolate;
    seconds["gather"] = result.seconds_gather;
    seconds["small_emitters"] = result.seconds_direct_emitters;

    add_elements(result.build, out);
    add_surface_solution(result.build.elements, result.solve.radiance, result.colors, out);
    // The light arriving without the surface's colour (BakeResult::light_colors; the zonal bake has none).
    if (result.light_colors.input_corner.size() == result.colors.input_corner.size()) {
        out["corner_light"] = to_numpy(result.light_colors.input_corner);
        out["element_corner_light"] = element_corner_array(result.light_colors.element_corner);
    }
    out["iterations"] = result.solve.iterations;
    out["shots"] = result.solve.shots;
    out["residual"] = result.solve.residual;
    out["residual_history"] = result.solve.residual_history;
    out["converged"] = result.solve.converged;
    out["matrix_stored"] = result.matrix_stored;
    out["matrix_nonzeros"] = result.matrix_nonzeros;
    out["matrix_bytes"] = result.matrix_bytes;
    out["seconds"] = seconds;
    if (result.direct_emitters > 0) out["direct_emitters"] = result.direct_emitters;
    if (result.gathered_points + result.buried_points > 0) {  // the final gather ran
        py::dict gather;
        gather["points"] = result.gathered_points;
        gather["buried"] = result.buried_points;
        out["final_gather"] = gather;
    }
}

void add_surface_solution(const Elements& elements, const std::vector<Rgb>& radiance, const CornerColors& colors,
                          py::dict& out) {
    out["corner_radiance"] = to_numpy(colors.input_corner);
    out["element_corner_radiance"] = element_corner_array(colors.element_corner);
    out["element_radiance"] = to_numpy(radiance);
    // What the solve used per element, so the add-on can account for power: emission includes
    // the lamps' first reflection (rho E / pi), reflectance is the capped input.
    out["element_emission"] = to_numpy(elements.emission);
    out["element_reflectance"] = to_numpy(elements.reflectance);
}

}  // namespace radiosity::python
