/// @file corner_approach.cpp
/// @brief Directions towards each corner's first fan triangle's centroid (corner_approach.h).
#include "output/corner_approach.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace radiosity::detail {

std::vector<Vec3> corner_approach(const Elements& elements, const int32_t* face_offsets, std::size_t face_count) {
    std::vector<Vec3> approach(elements.vertices.size(), Vec3(0.0f));
    if (face_offsets == nullptr) return approach;
    for (std::size_t f = 0; f < face_count; ++f) {
        const int32_t first = face_offsets[f], count = face_offsets[f + 1] - first;
        if (count < 3) continue;
        auto vertex = [&](int32_t k) { return elements.corner_vertex[std::size_t(first + k)]; };
        bool whole = true;
        for (int32_t k = 0; k < count; ++k) whole = whole && vertex(k) >= 0;
        if (!whole) continue;  // a skipped polygon
        auto at = [&](int32_t k) { return glm::dvec3(elements.vertices[std::size_t(vertex(k))]); };
        for (int32_t k = 0; k < count; ++k) {
            // The first fan triangle holding corner k: (0 1 2) for corners 0 to 2, else (0 k-1 k).
            const int32_t b = k <= 2 ? 1 : k - 1, c = k <= 2 ? 2 : k;
            const glm::dvec3 towards = (at(0) + at(b) + at(c)) / 3.0 - at(k);
            const double length = glm::length(towards);
            if (length > 0.0) approach[std::size_t(vertex(k))] = Vec3(towards / length);
        }
    }
    return approach;
}

float bake_offset(const Vec3& corner, float scene_size) {
    const float floor = std::min(1.0f, scene_size);
    return 1e-4f * std::max({floor, std::abs(corner.x), std::abs(corner.y), std::abs(corner.z)});
}

}  // namespace radiosity::detail
