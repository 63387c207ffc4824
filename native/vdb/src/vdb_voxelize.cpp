/// @file vdb_voxelize.cpp
/// @brief The inside of a closed mesh as a per-cell volume fraction, through OpenVDB's level sets.
#include "common/types.h"
#include "radiosity/vdb_io.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace radiosity::vdb {

WorldGrid voxelize_mesh_interior(const float* positions, std::size_t vertex_count, const int32_t* face_offsets,
                                 const int32_t* corner_vertices, std::size_t face_count, double cell_size,
                                 int samples) {
    if (!(cell_size > 0.0) || samples < 1) throw InputError("cell size must be > 0 and samples >= 1");
    openvdb::initialize();
    std::vector<openvdb::Vec3s> points(vertex_count);
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (std::size_t v = 0; v < vertex_count; ++v) {
        points[v] = openvdb::Vec3s(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
        for (int a = 0; a < 3; ++a) {
            if (!std::isfinite(positions[3 * v + a]))
                throw InputError("vertex " + std::to_string(v) + " is not finite");
            lo[a] = std::min(lo[a], double(positions[3 * v + a]));
            hi[a] = std::max(hi[a], double(positions[3 * v + a]));
        }
    }
    std::vector<openvdb::Vec3I> triangles;
    for (std::size_t f = 0; f < face_count; ++f)
        for (int32_t k = face_offsets[f] + 1; k + 1 < face_offsets[f + 1]; ++k) {
            const int32_t a = corner_vertices[face_offsets[f]], b = corner_vertices[k], c = corner_vertices[k + 1];
            if (a < 0 || b < 0 || c < 0 || std::size_t(std::max({a, b, c})) >= vertex_count)
                throw InputError("polygon " + std::to_string(f) + ": vertex index out of range");
            triangles.emplace_back(a, b, c);
        }

    WorldGrid out;
    out.cell_size = cell_size;
    if (triangles.empty()) return out;
    out.origin = lo;
    for (int a = 0; a < 3; ++a) out.dims[a] = std::max(1, int(std::ceil((hi[a] - lo[a]) / cell_size - 1e-9)));
    out.values.assign(out.cell_count(), 0.0f);

    // Fine voxel (i, j, k) is sample point (i % s, j % s, k % s) of cell (i / s, j / s, k / s).
    const double fine = cell_size / samples;
    auto transform = openvdb::math::Transform::createLinearTransform(fine);
    transform->postTranslate(openvdb::Vec3d(lo.x, lo.y, lo.z) + 0.5 * fine);
    const auto distance = openvdb::tools::meshToLevelSet<openvdb::FloatGrid>(*transform, points, triangles);
    const auto accessor = distance->getConstAccessor();
    const float per_sample = 1.0f / float(samples * samples * samples);
    for (int32_t z = 0; z < out.dims[2] * samples; ++z)
        for (int32_t y = 0; y < out.dims[1] * samples; ++y)
            for (int32_t x = 0; x < out.dims[0] * samples; ++x)
                if (accessor.getValue(openvdb::Coord(x, y, z)) < 0.0f)
                    out.values[x / samples +
                               std::size_t(out.dims[0]) * (y / samples + std::size_t(out.dims[1]) * (z / samples))] +=
                        per_sample;
    return out;
}

}  // namespace radiosity::vdb
