/// @file intersection_cut.cpp
/// @brief Convex pieces along intersection lines, and cut-edge marks on their elements (see intersection_cut.h).
#include "geometry/intersection_cut.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace radiosity::detail {
namespace {

/// The piece's two halves about the line through `on` with unit side normal `side`, or false when
/// all its corners are within `tolerance` of one side (the line only touches it).
bool split(const Piece& piece, const DVec3& on, const DVec3& side, double tolerance, Piece& left, Piece& right) {
    const std::size_t n = piece.points.size();
    std::vector<double> g(n);
    for (std::size_t k = 0; k < n; ++k) g[k] = glm::dot(side, piece.points[k] - on);
    if (*std::max_element(g.begin(), g.end()) <= tolerance || *std::min_element(g.begin(), g.end()) >= -tolerance)
        return false;
    left = {};
    right = {};
    for (std::size_t k = 0; k < n; ++k) {
        const std::size_t next = (k + 1) % n;
        // Corners on the line go to both halves; crossing points are computed once, so both halves
        // hold the same bits and their shared edge subdivides identically.
        if (g[k] >= -tolerance) left.points.push_back(piece.points[k]), left.corner.push_back(piece.corner[k]);
        if (g[k] <= tolerance) right.points.push_back(piece.points[k]), right.corner.push_back(piece.corner[k]);
        if ((g[k] > tolerance && g[next] < -tolerance) || (g[k] < -tolerance && g[next] > tolerance)) {
            const DVec3 x = piece.points[k] + (piece.points[next] - piece.points[k]) * (g[k] / (g[k] - g[next]));
            left.points.push_back(x), left.corner.push_back(-1);
            right.points.push_back(x), right.corner.push_back(-1);
        }
    }
    return true;
}

/// Where a point lies against the line through `a` along unit `u`: how far along it, how far off it.
struct LinePosition {
    double along, off;
};
LinePosition line_position(const DVec3& p, const DVec3& a, const DVec3& u) {
    const double along = glm::dot(p - a, u);
    return {along, glm::length((p - a) - along * u)};
}

/// Whether an end of segment `s` lies on the boundary of `piece` within `tolerance`, inside one of
/// its edges (not at a corner): a wall ending on the border of a piece beside it, whose edge then
/// runs on past the wall's end without a vertex there.
bool ends_on_edge(const Piece& piece, const CutSegment& s, double tolerance) {
    const std::size_t n = piece.points.size();
    for (const DVec3& end : {s.a, s.b})
        for (std::size_t k = 0; k < n; ++k) {
            const DVec3 a = piece.points[k], b = piece.points[(k + 1) % n];
            const double length = glm::length(b - a);
            if (!(length > 0.0)) continue;
            const LinePosition at = line_position(end, a, (b - a) / length);
            if (at.along > tolerance && at.along < length - tolerance && at.off <= tolerance) return true;
        }
    return false;
}

}  // namespace

std::vector<Piece> cut_polygon(const std::vector<DVec3>& p, const DVec3& normal, const CutSegment* begin,
                               const CutSegment* end, double tolerance) {
    std::vector<Piece> pieces;
    if (p.size() == 3 || is_convex(p, normal)) {
        Piece whole{p, {}};
        for (std::size_t k = 0; k < p.size(); ++k) whole.corner.push_back(static_cast<int32_t>(k));
        pieces.push_back(std::move(whole));
    } else {
        for (const auto& t : triangulate(p, normal))
            pieces.push_back({{p[t[0]], p[t[1]], p[t[2]]}, {t[0], t[1], t[2]}});
    }
    std::vector<Piece> next;
    for (const CutSegment* s = begin; s != end; ++s) {
        const DVec3 side = glm::normalize(glm::cross(normal, s->b - s->a));
        next.clear();
        for (const Piece& piece : pieces) {
            DVec3 a = s->a, b = s->b;
            Piece left, right;
            if ((clip_segment(piece.points, normal, tolerance, a, b) || ends_on_edge(piece, *s, tolerance)) &&
                split(piece, s->a, side, tolerance, left, right)) {
                next.push_back(std::move(left));
                next.push_back(std::move(right));
            } else {
                next.push_back(piece);
            }
        }
        pieces.swap(next);
    }
    return pieces;
}

void mark_cut_edges(Elements& elements, std::size_t first, const CutSegment* begin, const CutSegment* end,
                    double tolerance) {
    for (std::size_t e = first; e < elements.size(); ++e) {
        const int m = elements.is_triangle(e) ? 3 : 4;
        for (int k = 0; k < m; ++k) {
            const DVec3 v0(elements.vertices[elements.corners[e][k]]),
                v1(elements.vertices[elements.corners[e][(k + 1) % m]]);
            for (const CutSegment* s = begin; s != end; ++s) {
                const double length = glm::length(s->b - s->a);
                const DVec3 u = (s->b - s->a) / length;
                const double middle = line_position(0.5 * (v0 + v1), s->a, u).along;
                if (line_position(v0, s->a, u).off <= tolerance && line_position(v1, s->a, u).off <= tolerance &&
                    middle > 0.0 && middle < length) {
                    elements.cut_edges[e] |= uint8_t(1u << k);
                    break;
                }
            }
        }
    }
}

}  // namespace radiosity::detail
