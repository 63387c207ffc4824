/// @file vdb_io.h
/// @brief Media from OpenVDB files onto axis-aligned world grids, and baked grids back to files.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace radiosity::vdb {

/// An axis-aligned grid of cubic cells in world space: cell (x, y, z) covers
/// origin + cell_size * [x, x+1] x [y, y+1] x [z, z+1]; values are indexed
/// (x + dims[0] * (y + dims[1] * z)) * channels + channel.
struct WorldGrid {
    glm::dvec3 origin{0.0};
    double cell_size = 0.0;
    std::array<int32_t, 3> dims{0, 0, 0};
    int channels = 1;
    std::vector<float> values;

    std::size_t cell_count() const { return std::size_t(dims[0]) * dims[1] * dims[2]; }
};

/// Names and kinds of the grids in a file: {name, "float" | "vec3s" | other type name}.
std::vector<std::array<std::string, 2>> list_grids(const std::string& path);

/// Reads grid `name` (float or vec3s) from `path` and averages it over world cells of
/// `cell_size` metres (`samples`^3 trilinear samples per cell), covering the grid's active
/// voxels widened by one voxel (the reach of trilinear interpolation) after its own transform
/// and then `object_to_world` (Blender's object matrix). The cells start at that box's corner.
/// Throws std::runtime_error naming the file and grid when either is missing or unreadable.
WorldGrid read_world_grid(const std::string& path, const std::string& name, const glm::dmat4& object_to_world,
                          double cell_size, int samples = 2);

/// The inside of a closed polygon mesh (world space; n-gons fanned into triangles) as the fraction
/// of each world cell inside it, from `samples`^3 points per cell classified by OpenVDB's signed
/// distance (meshToLevelSet: closed but not necessarily manifold surfaces, normals ignored).
/// Cells start at the mesh's bounding-box corner.
WorldGrid voxelize_mesh_interior(const float* positions, std::size_t vertex_count, const int32_t* face_offsets,
                                 const int32_t* corner_vertices, std::size_t face_count, double cell_size,
                                 int samples = 2);

/// A grid to write: `values` has grid.channels (1 -> FloatGrid, 3 -> Vec3SGrid) per cell.
struct NamedGrid {
    std::string name;
    const WorldGrid* grid;
};

/// Writes the grids to `path` (overwriting it) as sparse OpenVDB grids: zero cells are inactive.
/// Each grid's transform maps voxel centres to world cell centres.
void write_grids(const std::string& path, const std::vector<NamedGrid>& grids);

}  // namespace radiosity::vdb
