/// @file near_field.h
/// @brief Analytic area-to-area form factors for near element pairs, replacing the hemi-cube's
/// centre-point values where the point-at-centre assumption breaks.
///
/// A hemi-cube at the centre of element i measures the factor from that point to j. When j is
/// closer than a few times the larger element's size (shared edges, a receiver under a large
/// shooter) that differs from the area-to-area factor F_ij = (1/A_i) int_{A_i} F_{dA->j} dA by
/// up to 100% (and more), and A_i F_ij != A_j F_ji. For such pairs we integrate the unoccluded
/// point-to-polygon factor (Lambert's contour integral) over sub-points of the smaller element,
/// which gives A_i F_ij and, by reciprocity, A_j F_ji identically, and keep the hemi-cube for what
/// it is good at: occlusion (the visible fraction) and everything far away.
#pragma once

#include "common/sparse.h"
#include "geometry/scene.h"

#include <glm/vec3.hpp>

namespace radiosity {

struct NearFieldSettings {
    bool enabled = false;
    /// A pair is near when its centres are closer than `distance` x the larger element's
    /// circumradius (centre to farthest corner). Typical 2 to 4; cost grows with its cube.
    float distance = 3.0f;
    /// The smaller element is integrated with an s x s Gauss-Legendre rule over its bilinear
    /// parameters (composite 4-point rules beyond s = 4). 4 meets Howell's shared-edge and opposed
    /// unit squares to 5e-6 (the five-digit references' rounding).
    int sub_points = 4;
};

/// One edge's term of Lambert's contour integral, seen from a point with unit normal n: the angle
/// the edge a -> b (relative to the point) subtends, times n . (a x b) / |a x b|. A polygon's
/// factor is the sum over its edges, in its winding, over 2 pi (in absolute value).
double contour_term(const glm::dvec3& n, const glm::dvec3& a, const glm::dvec3& b);

/// Unoccluded form factor from a point x with unit normal n to a planar polygon (its front side,
/// `polygon_normal`), Lambert's contour integral over the part of it above x's tangent plane.
double point_to_polygon(const glm::dvec3& x, const glm::dvec3& n, const glm::dvec3* polygon, int count,
                        const glm::dvec3& polygon_normal);

/// The largest distance from element i's centre to its corners.
double circumradius(const Elements& elements, int32_t i);

/// Unoccluded A_i F_ij (= A_j F_ji): the point-to-polygon factor integrated over s x s sub-points
/// of the smaller element towards the larger one. Symmetric in i and j, bit for bit.
double area_flux(const Elements& elements, int32_t i, int32_t j, int sub_points);

/// Replaces the near entries of row i (rendered by a hemi-cube of resolution `resolution` at i's
/// centre) by area_flux / A_i times the fraction of j the hemi-cube saw, then rescales the far
/// entries so that the row keeps the hemi-cube's coverage (a closed row still sums to 1); a row
/// never sums above 1.
void correct_near_field(const Elements& elements, int32_t i, int resolution, const NearFieldSettings& settings,
                        SparseRow& row);

}  // namespace radiosity
