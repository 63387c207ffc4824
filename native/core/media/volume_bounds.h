/// @file volume_bounds.h
/// @brief The box of a medium's occupied voxels (K_t > 0), in voxels and in world space (internal).
#pragma once

#include "media/volume.h"

#include <array>
#include <vector>

namespace radiosity {

/// Voxels [lo, hi) along each axis hold every zone of the medium; empty when it has none.
struct OccupiedBox {
    bool empty = true;
    std::array<int32_t, 3> lo{0, 0, 0}, hi{0, 0, 0};
    Vec3 world_lo{0.0f}, world_hi{0.0f};

    /// True when the interiors intersect (touching faces do not overlap).
    bool overlaps(const OccupiedBox& o) const {
        if (empty || o.empty) return false;
        for (int a = 0; a < 3; ++a)
            if (!(world_lo[a] < o.world_hi[a] && o.world_lo[a] < world_hi[a])) return false;
        return true;
    }
};

inline OccupiedBox occupied_box(const Medium& m) {
    OccupiedBox box;
    box.lo = m.dims;
    for (int32_t z = 0; z < m.dims[2]; ++z)
        for (int32_t y = 0; y < m.dims[1]; ++y)
            for (int32_t x = 0; x < m.dims[0]; ++x) {
                const Rgb& K = m.extinction[m.index(x, y, z)];
                if (!(K.r > 0.0 || K.g > 0.0 || K.b > 0.0)) continue;
                const std::array<int32_t, 3> v{x, y, z};
                for (int a = 0; a < 3; ++a) {
                    box.lo[a] = std::min(box.lo[a], v[a]);
                    box.hi[a] = std::max(box.hi[a], v[a] + 1);
                }
                box.empty = false;
            }
    if (box.empty) return OccupiedBox();
    for (int a = 0; a < 3; ++a) {
        box.world_lo[a] = m.origin[a] + m.voxel_size * box.lo[a];
        box.world_hi[a] = m.origin[a] + m.voxel_size * box.hi[a];
    }
    return box;
}

inline std::vector<OccupiedBox> occupied_boxes(const std::vector<Medium>& media) {
    std::vector<OccupiedBox> boxes;
    boxes.reserve(media.size());
    for (const Medium& m : media) boxes.push_back(occupied_box(m));
    return boxes;
}

}  // namespace radiosity
