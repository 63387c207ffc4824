/// @file vdb_write.cpp
/// @brief Writing world grids as sparse OpenVDB grids (zero cells stay inactive).
#include "common/types.h"
#include "radiosity/vdb_io.h"

#include <openvdb/openvdb.h>

#include <stdexcept>

namespace radiosity::vdb {
namespace {

/// Voxel centres at the world cells' centres: index (x, y, z) -> origin + (x + 0.5) * cell_size.
openvdb::math::Transform::Ptr cell_transform(const WorldGrid& grid) {
    auto transform = openvdb::math::Transform::createLinearTransform(grid.cell_size);
    transform->postTranslate(openvdb::Vec3d(grid.origin.x, grid.origin.y, grid.origin.z) + 0.5 * grid.cell_size);
    return transform;
}

template <typename GridType, typename Value>
typename GridType::Ptr to_vdb(const WorldGrid& grid, const std::string& name, Value value) {
    auto out = GridType::create();
    out->setName(name);
    out->setTransform(cell_transform(grid));
    auto accessor = out->getAccessor();
    for (int32_t z = 0; z < grid.dims[2]; ++z)
        for (int32_t y = 0; y < grid.dims[1]; ++y)
            for (int32_t x = 0; x < grid.dims[0]; ++x) {
                const std::size_t cell = x + std::size_t(grid.dims[0]) * (y + std::size_t(grid.dims[1]) * z);
                const auto v = value(cell);
                if (v != openvdb::zeroVal<typename GridType::ValueType>())
                    accessor.setValue(openvdb::Coord(x, y, z), v);
            }
    return out;
}

}  // namespace

void write_grids(const std::string& path, const std::vector<NamedGrid>& grids) {
    openvdb::initialize();
    openvdb::GridPtrVec out;
    for (const NamedGrid& named : grids) {
        const WorldGrid& g = *named.grid;
        if (g.values.size() != g.cell_count() * std::size_t(g.channels))
            throw InputError("grid '" + named.name + "': values do not match dims x channels");
        if (g.channels == 1) {
            out.push_back(to_vdb<openvdb::FloatGrid>(g, named.name, [&](std::size_t c) { return g.values[c]; }));
        } else if (g.channels == 3) {
            out.push_back(to_vdb<openvdb::Vec3SGrid>(g, named.name, [&](std::size_t c) {
                return openvdb::Vec3s(g.values[3 * c], g.values[3 * c + 1], g.values[3 * c + 2]);
            }));
        } else {
            throw InputError("grid '" + named.name + "': 1 or 3 channels, not " + std::to_string(g.channels));
        }
    }
    try {
        openvdb::io::File(path).write(out);
    } catch (const openvdb::Exception& e) {
        throw FileError("cannot write OpenVDB file '" + path + "': " + e.what());
    }
}

}  // namespace radiosity::vdb
