/// @file vdb_read.cpp
/// @brief Reading an OpenVDB grid onto an axis-aligned world grid by box-averaged trilinear samples.
#include "common/types.h"
#include "radiosity/vdb_io.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>
#include <tbb/parallel_for.h>

#include <glm/gtc/matrix_inverse.hpp>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace radiosity::vdb {
namespace {

openvdb::GridBase::Ptr open_grid(const std::string& path, const std::string& name) {
    openvdb::initialize();
    openvdb::io::File file(path);
    try {
        file.open();
    } catch (const openvdb::Exception& e) {
        throw FileError("cannot open OpenVDB file '" + path + "': " + e.what());
    }
    if (!file.hasGrid(name)) throw FileError("OpenVDB file '" + path + "' has no grid '" + name + "'");
    openvdb::GridBase::Ptr grid = file.readGrid(name);
    file.close();
    return grid;
}

/// World-space box of where the grid's trilinear reconstruction is non-zero: the active voxels'
/// centres widened by one voxel, so resampling keeps all of the grid's mass.
void world_bounds(const openvdb::GridBase& grid, const glm::dmat4& object_to_world, glm::dvec3& lo, glm::dvec3& hi) {
    const openvdb::CoordBBox box = grid.evalActiveVoxelBoundingBox();
    lo = glm::dvec3(std::numeric_limits<double>::infinity());
    hi = -lo;
    for (int corner = 0; corner < 8; ++corner) {
        const openvdb::Vec3d index((corner & 1 ? box.max().x() + 1.0 : box.min().x() - 1.0),
                                   (corner & 2 ? box.max().y() + 1.0 : box.min().y() - 1.0),
                                   (corner & 4 ? box.max().z() + 1.0 : box.min().z() - 1.0));
        const openvdb::Vec3d local = grid.transform().indexToWorld(index);
        const glm::dvec3 world(object_to_world * glm::dvec4(local.x(), local.y(), local.z(), 1.0));
        lo = glm::min(lo, world);
        hi = glm::max(hi, world);
    }
}

template <typename GridType, typename Store>
void resample(const GridType& grid, const glm::dmat4& world_to_object, WorldGrid& out, int samples, Store store) {
    const double step = out.cell_size / samples;
    const double weight = 1.0 / (double(samples) * samples * samples);
    tbb::parallel_for(0, out.dims[2], [&](int32_t z) {
        auto accessor = grid.getConstAccessor();
        openvdb::tools::GridSampler<decltype(accessor), openvdb::tools::BoxSampler> sampler(accessor, grid.transform());
        for (int32_t y = 0; y < out.dims[1]; ++y)
            for (int32_t x = 0; x < out.dims[0]; ++x) {
                typename GridType::ValueType sum = openvdb::zeroVal<typename GridType::ValueType>();
                for (int k = 0; k < samples * samples * samples; ++k) {
                    const glm::dvec3 offset((k % samples + 0.5) * step, ((k / samples) % samples + 0.5) * step,
                                            (k / (samples * samples) + 0.5) * step);
                    const glm::dvec3 world = out.origin + glm::dvec3(x, y, z) * out.cell_size + offset;
                    const glm::dvec3 local(world_to_object * glm::dvec4(world, 1.0));
                    sum = sum + sampler.wsSample(openvdb::Vec3d(local.x, local.y, local.z));
                }
                store(x + std::size_t(out.dims[0]) * (y + std::size_t(out.dims[1]) * z), sum, weight);
            }
    });
}

}  // namespace

std::vector<std::array<std::string, 2>> list_grids(const std::string& path) {
    openvdb::initialize();
    openvdb::io::File file(path);
    try {
        file.open(false);
    } catch (const openvdb::Exception& e) {
        throw FileError("cannot open OpenVDB file '" + path + "': " + e.what());
    }
    std::vector<std::array<std::string, 2>> grids;
    for (auto it = file.beginName(); it != file.endName(); ++it)
        grids.push_back({it.gridName(), file.readGridMetadata(it.gridName())->valueType()});
    file.close();
    return grids;
}

WorldGrid read_world_grid(const std::string& path, const std::string& name, const glm::dmat4& object_to_world,
                          double cell_size, int samples) {
    if (!(cell_size > 0.0) || samples < 1) throw InputError("cell size must be > 0 and samples >= 1");
    const openvdb::GridBase::Ptr base = open_grid(path, name);
    WorldGrid out;
    out.cell_size = cell_size;
    if (base->empty()) return out;
    glm::dvec3 lo, hi;
    world_bounds(*base, object_to_world, lo, hi);
    out.origin = lo;
    for (int a = 0; a < 3; ++a) out.dims[a] = std::max(1, int(std::ceil((hi[a] - lo[a]) / cell_size - 1e-9)));
    const glm::dmat4 world_to_object = glm::inverse(object_to_world);

    if (auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(base)) {
        out.channels = 1;
        out.values.assign(out.cell_count(), 0.0f);
        resample(*grid, world_to_object, out, samples,
                 [&](std::size_t cell, float sum, double w) { out.values[cell] = float(sum * w); });
    } else if (auto grid = openvdb::gridPtrCast<openvdb::Vec3SGrid>(base)) {
        out.channels = 3;
        out.values.assign(3 * out.cell_count(), 0.0f);
        resample(*grid, world_to_object, out, samples, [&](std::size_t cell, const openvdb::Vec3s& sum, double w) {
            for (int c = 0; c < 3; ++c) out.values[3 * cell + c] = float(sum[c] * w);
        });
    } else {
        throw FileError("grid '" + name + "' in '" + path + "' is " + base->valueType() +
                        "; only float and vec3s grids can be read");
    }
    return out;
}

}  // namespace radiosity::vdb
