/// @file weld.cpp
/// @brief Position welding by quantised cells (see weld.h).
#include "geometry/weld.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace radiosity::detail {
namespace {

struct Cell {
    int64_t x, y, z;
    bool operator==(const Cell& o) const { return x == o.x && y == o.y && z == o.z; }
};

struct CellHash {
    std::size_t operator()(const Cell& c) const {
        auto h = static_cast<uint64_t>(c.x) * 0x9E3779B97F4A7C15ull;
        h ^= static_cast<uint64_t>(c.y) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
        h ^= static_cast<uint64_t>(c.z) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
        return static_cast<std::size_t>(h);
    }
};

}  // namespace

float weld_tolerance(const std::vector<Vec3>& points) {
    if (points.empty()) return 1.0f;
    Vec3 lo = points[0], hi = points[0];
    float magnitude = 0.0f;
    for (const Vec3& p : points) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
        magnitude = std::max({magnitude, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    }
    // Never below float round-off at these coordinates (a small scene far from the origin),
    // nor zero (a scene collapsed to a point).
    const float round_off = 16.0f * std::numeric_limits<float>::epsilon() * magnitude;
    return std::max({1e-5f * glm::length(hi - lo), round_off, std::numeric_limits<float>::min()});
}

std::vector<int32_t> weld_points(const std::vector<Vec3>& points, float tolerance, std::size_t& count) {
    std::unordered_map<Cell, int32_t, CellHash> representative;  // cell -> id of the point that opened it
    representative.reserve(points.size());
    std::vector<int32_t> id(points.size());
    std::vector<Vec3> position;  // of each id's first point
    for (std::size_t v = 0; v < points.size(); ++v) {
        const Vec3& p = points[v];
        const Cell c{static_cast<int64_t>(std::floor(p.x / tolerance)),
                     static_cast<int64_t>(std::floor(p.y / tolerance)),
                     static_cast<int64_t>(std::floor(p.z / tolerance))};
        auto within = [&](const Cell& cell) {
            const auto it = representative.find(cell);
            if (it == representative.end()) return -1;
            const Vec3 d = glm::abs(position[it->second] - p);
            return d.x <= tolerance && d.y <= tolerance && d.z <= tolerance ? it->second : -1;
        };
        // The point's own cell first: a mesh's repeated vertices find their twin there at once.
        int32_t found = within(c);
        for (int64_t dx = -1; dx <= 1 && found < 0; ++dx)
            for (int64_t dy = -1; dy <= 1 && found < 0; ++dy)
                for (int64_t dz = -1; dz <= 1 && found < 0; ++dz)
                    if (dx || dy || dz) found = within({c.x + dx, c.y + dy, c.z + dz});
        if (found < 0) {
            found = static_cast<int32_t>(position.size());
            position.push_back(p);
            representative.emplace(c, found);  // a cell opens once: its later points lie within tolerance
        }
        id[v] = found;
    }
    count = position.size();
    return id;
}

}  // namespace radiosity::detail
