/// @file flat_places.h
/// @brief Element vertices that stand for one point of a flat surface (internal; final_gather.h).
///
/// Every face keeps its own element vertices, so where the faces of a tessellated wall meet, one
/// place holds four vertices, and the final gather's field and each output corner's direct light
/// were computed four times at what is one point of the surface: the same place, the same plane,
/// the same seeds (they come from the place). Where the light there is continuous, once is enough.
/// It is continuous at a place inside one flat stretch of surface: no other plane meets it there
/// (a seam: a room's edge, a block's foot), no occluder's corner stands on it (a turning vertex), no
/// intersection or contact line passes through it (Elements::cut_edges), and its faces do not
/// overlap (their corner angles there sum to at most a full turn: coplanar faces lying on each
/// other are left to the gather's buried-point logic).
#pragma once

#include "geometry/scene.h"

#include <cstdint>
#include <vector>

namespace radiosity::detail {

/// Per element vertex, the vertex whose light it may take (itself where it takes none): the lowest
/// vertex of its flat place (see the top of this file). `place`: the welded vertex of each element
/// vertex (`places` of them); `seam`, `turning`: per element vertex, as final_gather finds them.
std::vector<int32_t> flat_place_vertices(const Elements& elements, const std::vector<int32_t>& place,
                                         std::size_t places, const std::vector<uint8_t>& seam,
                                         const std::vector<uint8_t>& turning);

}  // namespace radiosity::detail
