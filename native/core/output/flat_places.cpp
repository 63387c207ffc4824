/// @file flat_places.cpp
/// @brief Element vertices that stand for one point of a flat surface (flat_places.h).
#include "output/flat_places.h"

#include <glm/geometric.hpp>

#include <array>
#include <cmath>
#include <map>

namespace radiosity::detail {
namespace {

/// Places where the light may be discontinuous: seams, turning vertices, and the ends of cut edges.
std::vector<uint8_t> broken_places(const Elements& elements, const std::vector<int32_t>& place, std::size_t places,
                                   const std::vector<uint8_t>& seam, const std::vector<uint8_t>& turning) {
    std::vector<uint8_t> broken(places, 0);
    for (std::size_t v = 0; v < elements.vertices.size(); ++v)
        if (seam[v] || turning[v]) broken[std::size_t(place[v])] = 1;
    for (std::size_t e = 0; e < elements.cut_edges.size(); ++e) {
        const int count = elements.corner_count(e);
        for (int k = 0; k < count; ++k)
            if ((elements.cut_edges[e] >> k) & 1u) {
                broken[std::size_t(place[elements.corners[e][k]])] = 1;
                broken[std::size_t(place[elements.corners[e][(k + 1) % count]])] = 1;
            }
    }
    return broken;
}

/// The angle of element e at its corner k.
double corner_angle(const Elements& elements, std::size_t e, int k) {
    const int count = elements.corner_count(e);
    const glm::dvec3 at(elements.vertices[elements.corners[e][k]]);
    const glm::dvec3 to_next = glm::dvec3(elements.vertices[elements.corners[e][(k + 1) % count]]) - at;
    const glm::dvec3 to_previous = glm::dvec3(elements.vertices[elements.corners[e][(k + count - 1) % count]]) - at;
    return std::atan2(glm::length(glm::cross(to_next, to_previous)), glm::dot(to_next, to_previous));
}

}  // namespace

std::vector<int32_t> flat_place_vertices(const Elements& elements, const std::vector<int32_t>& place,
                                         std::size_t places, const std::vector<uint8_t>& seam,
                                         const std::vector<uint8_t>& turning) {
    const std::vector<uint8_t> broken = broken_places(elements, place, places, seam, turning);
    struct Group {
        int32_t lowest;
        double angle;
    };
    std::map<std::array<int64_t, 4>, Group> groups;  // by place and normal
    std::vector<std::array<int64_t, 4>> key_of(elements.vertices.size());
    std::vector<uint8_t> keyed(elements.vertices.size(), 0);
    for (std::size_t e = 0; e < elements.size(); ++e) {
        if (elements.is_back(e)) continue;
        const Vec3 n = elements.normal[e];
        for (int k = 0; k < elements.corner_count(e); ++k) {
            const int32_t v = elements.corners[e][k];
            const std::size_t p = std::size_t(place[std::size_t(v)]);
            if (broken[p]) continue;
            const std::array<int64_t, 4> key{int64_t(p), std::llround(n.x * 1e4), std::llround(n.y * 1e4),
                                             std::llround(n.z * 1e4)};
            auto [at, fresh] = groups.try_emplace(key, Group{v, 0.0});
            at->second.lowest = std::min(at->second.lowest, v);
            at->second.angle += corner_angle(elements, e, k);
            key_of[std::size_t(v)] = key;
            keyed[std::size_t(v)] = 1;
        }
    }
    std::vector<int32_t> same(elements.vertices.size());
    for (std::size_t v = 0; v < same.size(); ++v) {
        same[v] = int32_t(v);
        if (!keyed[v]) continue;
        const Group& group = groups.at(key_of[v]);
        if (group.angle <= 2.0 * M_PI * (1.0 + 1e-3)) same[v] = group.lowest;
    }
    return same;
}

}  // namespace radiosity::detail
