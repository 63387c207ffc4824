/// @file near_field.cpp
/// @brief Near-field correction of form-factor rows: Lambert's contour integral over sub-points.
///
/// Lambert: from a point with normal n, a polygon with corners r_k (relative to the point) has
/// F = 1/(2 pi) |sum_k angle(r_k, r_k+1) n . unit(r_k x r_k+1)|, exact for the polygon's part
/// above the point's tangent plane, which we clip first (Sutherland-Hodgman).
#include "transport/near_field.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace radiosity {
namespace {

using DVec3 = glm::dvec3;

/// Up to 4 corners, clipped by one plane: at most 5.
using Polygon = std::array<DVec3, 8>;

int element_corners(const Elements& e, int32_t i, DVec3* out) {
    const int count = e.is_triangle(i) ? 3 : 4;
    for (int k = 0; k < count; ++k) out[k] = DVec3(e.vertices[e.corners[i][k]]);
    return count;
}

/// Gauss-Legendre nodes and weights on [0, 1], s = 1..4 (beyond that composite rules: see sub_points).
struct GaussRule {
    std::array<double, 4> node, weight;
};
const GaussRule& gauss_rule(int s) {
    static const std::array<GaussRule, 4> rules{{
        {{0.5}, {1.0}},
        {{0.2113248654051871, 0.7886751345948129}, {0.5, 0.5}},
        {{0.1127016653792583, 0.5, 0.8872983346207417}, {5.0 / 18, 8.0 / 18, 5.0 / 18}},
        {{0.0694318442029737, 0.3300094782075719, 0.6699905217924281, 0.9305681557970263},
         {0.1739274225687269, 0.3260725774312731, 0.3260725774312731, 0.1739274225687269}},
    }};
    return rules[s - 1];
}

/// Sub-points of element i with their quadrature weights (areas): a product Gauss rule over the
/// element's bilinear parameters.
template <class Visit>
void sub_points(const Elements& e, int32_t i, int s, Visit visit) {
    DVec3 p[4];
    // A triangle is the quad (p0, p1, p2, p0) with one edge collapsed (Duffy): the Jacobian below
    // goes to zero there and the product rule stays exact for polynomials.
    if (element_corners(e, i, p) == 3) p[3] = p[0];
    // Gauss-Legendre in each bilinear parameter (s <= 4), s/4 x s/4 cells of 4-point rules beyond.
    const int cells = s <= 4 ? 1 : (s + 3) / 4;
    const GaussRule& rule = gauss_rule(s <= 4 ? s : 4);
    const int q = s <= 4 ? s : 4;
    for (int ca = 0; ca < cells; ++ca)
        for (int cb = 0; cb < cells; ++cb)
            for (int a = 0; a < q; ++a)
                for (int b = 0; b < q; ++b) {
                    const double x = (ca + rule.node[a]) / cells, y = (cb + rule.node[b]) / cells;
                    const DVec3 point =
                        (1 - x) * (1 - y) * p[0] + x * (1 - y) * p[1] + x * y * p[2] + (1 - x) * y * p[3];
                    const DVec3 dx = (1 - y) * (p[1] - p[0]) + y * (p[2] - p[3]),
                                dy = (1 - x) * (p[3] - p[0]) + x * (p[2] - p[1]);
                    visit(point,
                          glm::length(glm::cross(dx, dy)) * rule.weight[a] * rule.weight[b] / double(cells * cells));
                }
}

/// Keeps the part of `in` with n . (p - x) >= 0.
int clip_to_hemisphere(const DVec3& x, const DVec3& n, const DVec3* in, int count, Polygon& out) {
    int m = 0;
    for (int k = 0; k < count; ++k) {
        const DVec3 &a = in[k], &b = in[(k + 1) % count];
        const double da = glm::dot(n, a - x), db = glm::dot(n, b - x);
        if (da >= 0.0) out[m++] = a;
        if ((da < 0.0) != (db < 0.0)) out[m++] = a + (b - a) * (da / (da - db));
    }
    return m;
}

}  // namespace

double circumradius(const Elements& e, int32_t i) {
    DVec3 p[4];
    const int count = element_corners(e, i, p);
    double r = 0.0;
    for (int k = 0; k < count; ++k) r = std::max(r, glm::length(p[k] - DVec3(e.centre[i])));
    return r;
}

double point_to_polygon(const DVec3& x, const DVec3& n, const DVec3* polygon, int count, const DVec3& polygon_normal) {
    if (!(glm::dot(polygon_normal, x - polygon[0]) > 0.0)) return 0.0;  // behind or in its plane: sees no front
    Polygon clipped;
    const int m = clip_to_hemisphere(x, n, polygon, count, clipped);
    double sum = 0.0;
    for (int k = 0; k < m; ++k) sum += contour_term(n, clipped[k] - x, clipped[(k + 1) % m] - x);
    return std::abs(sum) / (2.0 * M_PI);
}

double contour_term(const DVec3& n, const DVec3& a, const DVec3& b) {
    const DVec3 ab = glm::cross(a, b);
    const double length = glm::length(ab);
    if (!(length > 0.0)) return 0.0;  // collinear with the point: the edge subtends no angle
    return std::atan2(length, glm::dot(a, b)) * glm::dot(n, ab) / length;
}

double area_flux(const Elements& e, int32_t i, int32_t j, int s) {
    // Integrate over the smaller element (ties by index) towards the larger: the integrand is
    // smoother there, and both orders of (i, j) run the same arithmetic.
    const bool i_smaller = e.area[i] < e.area[j] || (e.area[i] == e.area[j] && i < j);
    const int32_t from = i_smaller ? i : j, to = i_smaller ? j : i;
    DVec3 target[4];
    const int count = element_corners(e, to, target);
    const DVec3 n(e.normal[from]), target_normal(e.normal[to]);
    double flux = 0.0;
    sub_points(e, from, s, [&](const DVec3& x, double area) {
        flux += area * point_to_polygon(x, n, target, count, target_normal);
    });
    return flux;
}

void correct_near_field(const Elements& e, int32_t i, int resolution, const NearFieldSettings& settings,
                        SparseRow& row) {
    const DVec3 centre(e.centre[i]), normal(e.normal[i]);
    const double r_i = circumradius(e, i);
    double coverage = 0.0, near_before = 0.0, near_after = 0.0;
    std::vector<bool> near(row.col.size(), false);
    for (std::size_t k = 0; k < row.col.size(); ++k) {
        const int32_t j = row.col[k];
        const double F_hc = row.val[k];
        coverage += F_hc;
        const double reach = settings.distance * std::max(r_i, circumradius(e, j));
        if (!(glm::length(DVec3(e.centre[j]) - centre) < reach)) continue;
        DVec3 target[4];
        const int count = element_corners(e, j, target);
        const double F_centre = point_to_polygon(centre, normal, target, count, DVec3(e.normal[j]));
        if (!(F_centre > 0.0)) continue;
        // Seen whole, an element differs from its unoccluded centre value only by the hemi-cube's
        // outline error, outline cells over covered cells: a square w cells wide can lose
        // 1 - (floor(w) / w)^2 ~ 2 / w, w ~ N sqrt(pi F) / 2, i.e. 2.3 / (N sqrt(F)) (measured up to
        // 0.54 / (N sqrt(F)) on the near pairs of a closed box, 0.12 for a grid-aligned patch at
        // N = 256). Such entries count as fully visible, so that both directions of a pair agree.
        const double outline = 2.5 / (resolution * std::sqrt(F_centre));
        const double seen = F_hc >= (1.0 - outline) * F_centre ? 1.0 : F_hc / F_centre;
        const double F = seen * area_flux(e, i, j, settings.sub_points) / e.area[i];
        near[k] = true;
        near_before += F_hc;
        near_after += F;
        row.val[k] = static_cast<float>(F);
    }
    // A closed row (every cell saw an element: delta form factors sum to 1 within 1e-6) must still
    // sum to 1, or a furnace drifts: the near entries changed how the hemisphere is shared, so the
    // far entries give or take the difference (all entries, when the far ones cannot). An open row
    // keeps its far entries: the sky may be what the near entries gained from. No row exceeds 1.
    const double far = coverage - near_before;
    const bool closed = coverage >= 1.0 - 1e-5;
    const double target = closed ? coverage : std::min(1.0, near_after + far);
    if (closed) {
        const double far_scale = far > 0.0 && near_after <= coverage ? (coverage - near_after) / far : 1.0;
        for (std::size_t k = 0; k < row.col.size(); ++k)
            if (!near[k]) row.val[k] = static_cast<float>(row.val[k] * far_scale);
    }
    double sum = 0.0;
    for (float v : row.val) sum += v;
    if (sum > target || (closed && sum > 0.0))
        for (float& v : row.val) v = static_cast<float>(v * (target / sum));
}

}  // namespace radiosity
