/// @file coincident_faces.h
/// @brief Where elements of different polygons lie on each other, facing the same way (internal).
///
/// Game levels built from brushes, and models merged from parts, hold duplicate and overlapping
/// coplanar faces. Cycles' rays leave a point without an offset, skipping only the face they leave:
/// every ray from a point where another face lies on its own meets that face's back at distance 0,
/// and Cycles bakes the point black (so it renders such places, too). The final gather's rays leave
/// a hair above their point and would pass the other face, so the gather asks here instead.
#pragma once

#include "geometry/scene.h"

#include <vector>

namespace radiosity::detail {

class CoincidentFaces {
public:
    /// Pairs of front-facing elements of different polygons, facing the same way (normals within
    /// 0.8 degrees) in planes no farther apart than `tolerance` metres, whose bounding boxes meet.
    CoincidentFaces(const Elements& elements, float tolerance);

    /// Whether `x`, a point of element `e`, lies inside or on the edge of an element of another
    /// polygon that lies on `e`, as Cycles' rays meet a face at any point within it (a sliver's
    /// corner baked 2e-6 m inside the face under it bakes black) and at its edges (a corner baked
    /// towards its face's centre along the other face's edge bakes black: Embree's test is closed).
    /// On an edge means on its line in float arithmetic: within a quarter of a float's spacing at
    /// x (a sliver's corner baked 1.3 spacings outside the face beside it is lit in Cycles). There
    /// it is covered only where `e` goes on across the edge (the two overlap), not where `e` ends
    /// at it (neighbours in one plane).
    bool covered(const Vec3& x, std::size_t e) const;

    /// Elements with at least one such partner.
    std::size_t covered_elements() const;

private:
    /// Whether `p` lies in element `h`, on the inner side of each edge line; with `inwards`, also
    /// on or within `on_edge` metres outside some of them, whose inward normals are added there.
    bool inside(const glm::dvec3& p, std::size_t h, double on_edge, glm::dvec3* inwards = nullptr) const;

    const Elements& elements_;
    std::vector<std::vector<int32_t>> partners_;  ///< per element, sorted; empty for most
};

}  // namespace radiosity::detail
