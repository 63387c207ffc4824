/// @file emitter_groups.h
/// @brief The final gather's emitting elements, grouped by the polygon side (or coplanar faces) they
/// tile, and their exact unoccluded light at a point (internal; final_gather.h).
///
/// An emitting polygon is split into many elements, and a point's direct light needs each one's
/// point-to-polygon factor (Lambert's contour integral, near_field.h): a scene whose emitters are
/// split into thousands of elements paid for each at every point. A group's elements tile one
/// planar side, and the contour integral is additive over the tiles (the edges they share cancel,
/// so do collinear pieces of an edge at a T-vertex), so where the whole group lies above the point's
/// tangent plane and its elements emit alike, its factor is the integral over the edges no other
/// element of the group shares: one term per outline edge, whatever the element count. Elsewhere
/// (a group the tangent plane cuts, or one whose elements' emission differs) each element's factor
/// is taken and clipped on its own.
#pragma once

#include "geometry/scene.h"

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace radiosity::detail {

/// An element that emits: its corners and what direct light needs of it.
struct Emitter {
    int32_t element;
    std::array<glm::dvec3, 4> polygon;
    int count;
    glm::dvec3 normal;
    Rgb radiance;
    int32_t polygon_index;  ///< the input polygon it came from
    double area;
};

/// A run of emitters of one polygon side, and what its light at a point needs.
struct EmitterRun {
    std::size_t first = 0, last = 0;                  ///< its emitters
    bool uniform = true;                              ///< every emitter of the run emits the same
    std::vector<std::array<glm::dvec3, 2>> outline;   ///< directed edges no other emitter shares, straight runs joined
    glm::dvec3 normal{0.0}, point{0.0}, centre{0.0};  ///< its plane; the centre of its vertices
    double radius = 0.0;                              ///< from the centre to its farthest vertex
    /// Per emitter of the run and one more: the area of the emitters before it, summed in order.
    std::vector<double> area_before;
};

/// A run of emitters seen from a point.
struct EmitterGroup {
    std::size_t first = 0, last = 0;  ///< its emitters
    std::size_t run = 0;              ///< its EmitterRun
    Rgb light{0.0};                   ///< its exact unoccluded light at the point
    double area = 0.0;                ///< of its elements that face the point
    /// The run emits alike and lies wholly above the point's tangent plane: every emitter faces the
    /// point (EmitterGroups::faces is not set for them), and the cost at the point does not grow
    /// with their count.
    bool whole = false;
};

struct EmitterGroups {
    std::vector<EmitterGroup> groups;
    /// Per emitter of a group not whole: it faces the point (its factor there is positive).
    std::vector<uint8_t> faces;
    double total = 0.0;  ///< the groups' light, summed over their largest channels
};

/// The emitting elements: `emitted` above zero and an area.
std::vector<Emitter> emitting_elements(const Elements& elements, const std::vector<Rgb>& emitted);

/// The runs of `emitters` that lie on one polygon's side: consecutive, of one input polygon, with
/// normals within kSamePlane (a rotated polygon's elements differ in the last bits of their
/// normals; its back side's are opposite). A tessellated emitter's faces are polygons of their own:
/// the next polygon in the same plane, emitting the same and meeting the run at a corner, joins it,
/// so its light at a point is one contour integral over the whole emitter's outline.
std::vector<EmitterRun> emitter_runs(const Elements& elements, const std::vector<Emitter>& emitters);

/// Each run's exact unoccluded light at `x` (normal `n`) and which of its emitters face x.
EmitterGroups emitter_groups(const std::vector<Emitter>& emitters, const std::vector<EmitterRun>& runs,
                             const glm::dvec3& x, const glm::dvec3& n);

}  // namespace radiosity::detail
