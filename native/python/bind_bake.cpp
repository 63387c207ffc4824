/// @file bind_bake.cpp
/// @brief `_core.bake`: flat numpy arrays in, corner colours and statistics out.
#include "arrays.h"
#include "bindings.h"
#include "progress.h"

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

const char* defect_name(Defect defect) {
    switch (defect) {
        case Defect::ZeroArea: return "zero area";
        case Defect::NonFinite: return "non-finite coordinates";
        case Defect::TooFewCorners: return "fewer than three corners";
        case Defect::BadIndex: return "vertex index out of range";
    }
    return "unknown defect";
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

py::array_t<int32_t> corner_index_array(const std::vector<std::array<int32_t, 4>>& corners) {
    py::array_t<int32_t> out({static_cast<py::ssize_t>(corners.size()), py::ssize_t{4}});
    std::memcpy(out.mutable_data(), corners.data(), corners.size() * sizeof(corners[0]));
    return out;
}

py::dict bake_arrays(const Array<float>& positions, const Array<int32_t>& face_offsets,
                     const Array<int32_t>& corner_vertices, const Array<float>& reflectance,
                     const Array<float>& emission, const std::optional<Array<int32_t>>& material,
                     float element_size, int resolution, const std::string& method, double tolerance,
                     int max_iterations, float hard_edge_angle, bool ambient, const py::list& lights,
                     std::size_t matrix_budget_bytes,
                     const py::object& progress) {
    require_shape(positions, "positions", -1, 3);
    require_shape(face_offsets, "face_offsets", -1, 0);
    if (face_offsets.shape(0) < 1) throw py::value_error("face_offsets needs face_count + 1 entries (at least one)");
    const py::ssize_t faces = face_offsets.shape(0) - 1;
    require_shape(corner_vertices, "corner_vertices", -1, 0);
    require_shape(reflectance, "reflectance", faces, 3);
    require_shape(emission, "emission", faces, 3);
    if (material) require_shape(*material, "material", faces, 0);
    if (face_offsets.at(faces) != corner_vertices.shape(0))
        throw py::value_error("face_offsets[-1] must equal len(corner_vertices)");
    if (resolution < 8 || resolution % 2 != 0) throw py::value_error("resolution must be an even number >= 8");
    if (!(element_size >= 0.0f)) throw py::value_error("element_size must be >= 0");
    if (!(tolerance > 0.0)) throw py::value_error("tolerance must be > 0");
    if (max_iterations < 1) throw py::value_error("max_iterations must be >= 1");

    SceneInput input;
    input.positions = positions.data();
    input.vertex_count = static_cast<std::size_t>(positions.shape(0));
    input.face_offsets = face_offsets.data();
    input.corner_vertices = corner_vertices.data();
    input.face_count = static_cast<std::size_t>(faces);
    input.reflectance = reflectance.data();
    input.emission = emission.data();
    input.material = material ? material->data() : nullptr;

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

    ProgressBridge bridge(progress);
    BakeResult result;
    try {
        py::gil_scoped_release release;
        result = bake(input, settings, bridge.function());
    } catch (const Cancelled&) {
        bridge.rethrow_if_failed();
        throw;
    }

    const Elements& elements = result.build.elements;
    py::list skipped;
    for (const SkippedPolygon& s : result.build.skipped) skipped.append(py::make_tuple(s.polygon, defect_name(s.defect)));
    py::dict seconds;
    seconds["elements"] = result.seconds_elements;
    seconds["lights"] = result.seconds_lights;
    seconds["form_factors"] = result.seconds_form_factors;
    seconds["solve"] = result.seconds_solve;
    seconds["interpolate"] = result.seconds_interpolate;

    py::dict out;
    out["corner_radiance"] = to_numpy(result.colors.input_corner);
    out["element_vertices"] = to_numpy(elements.vertices);
    out["element_corners"] = corner_index_array(elements.corners);
    out["element_corner_radiance"] = element_corner_array(result.colors.element_corner);
    out["element_polygon"] = to_numpy(elements.polygon);
    out["element_radiance"] = to_numpy(result.solve.radiance);
    out["element_area"] = to_numpy(elements.area);
    out["skipped"] = skipped;
    out["elements"] = elements.size();
    out["iterations"] = result.solve.iterations;
    out["shots"] = result.solve.shots;
    out["residual"] = result.solve.residual;
    out["residual_history"] = result.solve.residual_history;
    out["converged"] = result.solve.converged;
    out["matrix_stored"] = result.matrix_stored;
    out["matrix_nonzeros"] = result.matrix_nonzeros;
    out["matrix_bytes"] = result.matrix_bytes;
    out["seconds"] = seconds;
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
}

}  // namespace radiosity::python
