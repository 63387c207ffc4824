/// @file bind_vdb.cpp
/// @brief OpenVDB input and output for the add-on: grids onto world zone grids, baked grids to files.
#include "arrays.h"
#include "bindings.h"

#include "radiosity/vdb_io.h"

#include <pybind11/stl.h>

namespace radiosity::python {

namespace {

/// Blender's matrix_world as a (4, 4) row-major array -> glm's column-major matrix.
glm::dmat4 to_glm(const Array<double>& m) {
    require_shape(m, "object_to_world", 4, 4);
    glm::dmat4 out;
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col) out[col][row] = m.at(row, col);
    return out;
}

/// {origin, cell_size, values (nz, ny, nx[, channels])} of a world grid.
py::dict grid_dict(const vdb::WorldGrid& grid) {
    std::vector<py::ssize_t> shape{grid.dims[2], grid.dims[1], grid.dims[0]};
    if (grid.channels == 3) shape.push_back(3);
    py::array_t<float> values(shape);
    std::copy(grid.values.begin(), grid.values.end(), values.mutable_data());
    py::dict out;
    out["origin"] = py::make_tuple(grid.origin.x, grid.origin.y, grid.origin.z);
    out["cell_size"] = grid.cell_size;
    out["values"] = values;
    return out;
}

py::dict read_grid(const std::string& path, const std::string& name, const Array<double>& object_to_world,
                   double cell_size, int samples) {
    const glm::dmat4 matrix = to_glm(object_to_world);
    vdb::WorldGrid grid;
    {
        py::gil_scoped_release release;
        grid = vdb::read_world_grid(path, name, matrix, cell_size, samples);
    }
    return grid_dict(grid);
}

py::dict voxelize_mesh(const Array<float>& positions, const Array<int32_t>& face_offsets,
                       const Array<int32_t>& corner_vertices, double cell_size, int samples) {
    require_shape(positions, "positions", -1, 3);
    require_shape(face_offsets, "face_offsets", -1, 0);
    require_shape(corner_vertices, "corner_vertices", -1, 0);
    if (face_offsets.shape(0) < 1 || face_offsets.at(face_offsets.shape(0) - 1) != corner_vertices.shape(0))
        throw InputError("face_offsets[-1] must equal len(corner_vertices)");
    vdb::WorldGrid grid;
    {
        py::gil_scoped_release release;
        grid = vdb::voxelize_mesh_interior(positions.data(), positions.shape(0), face_offsets.data(),
                                           corner_vertices.data(), face_offsets.shape(0) - 1, cell_size, samples);
    }
    return grid_dict(grid);
}

void write_grids(const std::string& path, const std::vector<double>& origin, double cell_size, const py::dict& grids) {
    if (origin.size() != 3) throw InputError("origin must be three numbers");
    if (!(cell_size > 0.0)) throw InputError("cell_size must be > 0");
    std::vector<vdb::WorldGrid> storage;
    std::vector<std::string> names;
    storage.reserve(grids.size());
    for (auto [key, value] : grids) {
        const auto name = key.cast<std::string>();
        const auto values = value.cast<Array<float>>();
        if (!(values.ndim() == 3 || (values.ndim() == 4 && values.shape(3) == 3)))
            throw InputError("grid '" + name + "' must have shape (nz, ny, nx) or (nz, ny, nx, 3)");
        vdb::WorldGrid grid;
        grid.origin = {origin[0], origin[1], origin[2]};
        grid.cell_size = cell_size;
        grid.dims = {int32_t(values.shape(2)), int32_t(values.shape(1)), int32_t(values.shape(0))};
        grid.channels = values.ndim() == 4 ? 3 : 1;
        grid.values.assign(values.data(), values.data() + values.size());
        storage.push_back(std::move(grid));
        names.push_back(name);
    }
    std::vector<vdb::NamedGrid> named;
    for (std::size_t i = 0; i < storage.size(); ++i) named.push_back({names[i], &storage[i]});
    py::gil_scoped_release release;
    vdb::write_grids(path, named);
}

}  // namespace

void bind_vdb(py::module_& m) {
    using namespace pybind11::literals;
    m.def("vdb_grids", &vdb::list_grids, "[(name, value type)] of the grids in an OpenVDB file.", "path"_a);
    m.def("read_vdb_grid", &read_grid,
          "Grid `name` of an OpenVDB file averaged over world cells of `cell_size` (samples^3 per cell), "
          "after the object's matrix. Returns {origin, cell_size, values (nz, ny, nx[, 3])}.",
          "path"_a, "name"_a, "object_to_world"_a, "cell_size"_a, "samples"_a = 2);
    m.def("voxelize_mesh", &voxelize_mesh,
          "Fraction of each world cell inside a closed mesh (world-space arrays as bake() takes them), "
          "from samples^3 points per cell. Returns {origin, cell_size, values (nz, ny, nx)}.",
          "positions"_a, "face_offsets"_a, "corner_vertices"_a, "cell_size"_a, "samples"_a = 2);
    m.def("write_vdb", &write_grids,
          "Writes {name: values (nz, ny, nx[, 3])} as sparse OpenVDB grids whose voxel centres are the "
          "world cells' centres, origin + (index + 0.5) * cell_size.",
          "path"_a, "origin"_a, "cell_size"_a, "grids"_a);
}

}  // namespace radiosity::python
