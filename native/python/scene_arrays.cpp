#include "scene_arrays.h"

namespace radiosity::python {

namespace {

const char* defect_name(Defect defect) {
    switch (defect) {
        case Defect::ZeroArea:
            return "zero area";
        case Defect::NonFinite:
            return "non-finite coordinates";
        case Defect::TooFewCorners:
            return "fewer than three corners";
        case Defect::BadIndex:
            return "vertex index out of range";
    }
    return "unknown defect";
}

py::array_t<int32_t> corner_index_array(const std::vector<std::array<int32_t, 4>>& corners) {
    py::array_t<int32_t> out({static_cast<py::ssize_t>(corners.size()), py::ssize_t{4}});
    std::memcpy(out.mutable_data(), corners.data(), corners.size() * sizeof(corners[0]));
    return out;
}

}  // namespace

SceneInput scene_input(const Array<float>& positions, const Array<int32_t>& face_offsets,
                       const Array<int32_t>& corner_vertices, const Array<float>& reflectance,
                       const Array<float>& emission, const std::optional<Array<int32_t>>& material,
                       const std::optional<Array<uint8_t>>& front_only) {
    require_shape(positions, "positions", -1, 3);
    require_shape(face_offsets, "face_offsets", -1, 0);
    if (face_offsets.shape(0) < 1) throw InputError("face_offsets needs face_count + 1 entries (at least one)");
    const py::ssize_t faces = face_offsets.shape(0) - 1;
    require_shape(corner_vertices, "corner_vertices", -1, 0);
    require_shape(reflectance, "reflectance", faces, 3);
    require_shape(emission, "emission", faces, 3);
    if (material) require_shape(*material, "material", faces, 0);
    if (front_only) require_shape(*front_only, "front_only", faces, 0);
    if (face_offsets.at(faces) != corner_vertices.shape(0))
        throw InputError("face_offsets[-1] must equal len(corner_vertices)");

    SceneInput input;
    input.positions = positions.data();
    input.vertex_count = static_cast<std::size_t>(positions.shape(0));
    input.face_offsets = face_offsets.data();
    input.corner_vertices = corner_vertices.data();
    input.face_count = static_cast<std::size_t>(faces);
    input.reflectance = reflectance.data();
    input.emission = emission.data();
    input.material = material ? material->data() : nullptr;
    input.front_only = front_only ? front_only->data() : nullptr;
    return input;
}

void add_elements(const BuildResult& build, py::dict& out) {
    const Elements& elements = build.elements;
    py::list skipped;
    for (const SkippedPolygon& s : build.skipped) skipped.append(py::make_tuple(s.polygon, defect_name(s.defect)));
    out["element_vertices"] = to_numpy(elements.vertices);
    out["element_corners"] = corner_index_array(elements.corners);
    out["element_polygon"] = to_numpy(elements.polygon);
    out["element_area"] = to_numpy(elements.area);
    // Which elements are an emitting polygon's back side (Elements::side): solved, counted in the
    // power, not drawn or written (their corner colours are zero).
    py::array_t<bool> back(static_cast<py::ssize_t>(elements.size()));
    for (std::size_t e = 0; e < elements.size(); ++e) back.mutable_data()[e] = elements.is_back(e);
    out["element_back"] = back;
    out["elements"] = elements.size();
    out["skipped"] = skipped;
}

}  // namespace radiosity::python
