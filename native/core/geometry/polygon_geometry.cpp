/// @file polygon_geometry.cpp
/// @brief Area vector, convexity and ear clipping of planar polygons (see polygon_geometry.h).
#include "geometry/polygon_geometry.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cstddef>

namespace radiosity::detail {

DVec3 newell(const std::vector<DVec3>& p) {
    DVec3 n(0.0);
    for (std::size_t i = 0; i < p.size(); ++i) n += glm::cross(p[i], p[(i + 1) % p.size()]);
    return n;
}

bool straight(const DVec3& a, const DVec3& b, const DVec3& c, double sine) {
    const DVec3 u = b - a, v = c - b;
    const double lengths = glm::length(u) * glm::length(v);
    return glm::dot(u, v) > 0.0 && glm::length(glm::cross(u, v)) <= sine * lengths;
}

bool is_convex(const std::vector<DVec3>& p, const DVec3& normal) {
    for (std::size_t i = 0; i < p.size(); ++i) {
        const DVec3 &a = p[i], &b = p[(i + 1) % p.size()], &c = p[(i + 2) % p.size()];
        if (!(glm::dot(glm::cross(b - a, c - b), normal) > 0.0)) return false;
    }
    return true;
}

std::vector<std::array<int, 3>> triangulate(const std::vector<DVec3>& p, const DVec3& normal) {
    std::vector<int> ring(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) ring[i] = static_cast<int>(i);
    auto convex = [&](int a, int b, int c) { return glm::dot(glm::cross(p[b] - p[a], p[c] - p[b]), normal) > 0.0; };
    auto inside = [&](int q, int a, int b, int c) {
        return glm::dot(glm::cross(p[b] - p[a], p[q] - p[a]), normal) >= 0.0 &&
               glm::dot(glm::cross(p[c] - p[b], p[q] - p[b]), normal) >= 0.0 &&
               glm::dot(glm::cross(p[a] - p[c], p[q] - p[c]), normal) >= 0.0;
    };
    std::vector<std::array<int, 3>> triangles;
    while (ring.size() > 3) {
        const std::size_t m = ring.size();
        std::size_t ear = m;
        for (std::size_t i = 0; i < m && ear == m; ++i) {
            const int a = ring[(i + m - 1) % m], b = ring[i], c = ring[(i + 1) % m];
            if (!convex(a, b, c)) continue;
            bool empty = true;
            for (int q : ring)
                if (q != a && q != b && q != c && p[q] != p[a] && p[q] != p[b] && p[q] != p[c] && inside(q, a, b, c)) {
                    empty = false;
                    break;
                }
            if (empty) ear = i;
        }
        if (ear == m) ear = 0;  // self-intersecting outline: no true ear exists, cut any corner
        triangles.push_back({ring[(ear + m - 1) % m], ring[ear], ring[(ear + 1) % m]});
        ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(ear));
    }
    triangles.push_back({ring[0], ring[1], ring[2]});
    return triangles;
}

std::vector<std::vector<int>> convex_pieces(const std::vector<DVec3>& p, const DVec3& normal) {
    std::vector<std::vector<int>> pieces;
    for (const auto& t : triangulate(p, normal)) pieces.push_back({t[0], t[1], t[2]});
    // The piece holding the directed edge (u, v), or -1.
    auto holding = [&](int u, int v) {
        for (std::size_t k = 0; k < pieces.size(); ++k) {
            const std::vector<int>& q = pieces[k];
            for (std::size_t i = 0; i < q.size(); ++i)
                if (q[i] == u && q[(i + 1) % q.size()] == v) return int(k);
        }
        return -1;
    };
    std::vector<DVec3> points;
    for (std::size_t a = 0; a < pieces.size(); ++a) {
        for (std::size_t i = 0; i < pieces[a].size(); ++i) {
            const std::vector<int>& A = pieces[a];
            const int u = A[i], v = A[(i + 1) % A.size()];
            const int b = holding(v, u);
            if (b < 0 || std::size_t(b) == a) continue;
            // A from v round to u, then B's corners strictly between u and v.
            std::vector<int> joined;
            for (std::size_t k = 0; k < A.size(); ++k) joined.push_back(A[(i + 1 + k) % A.size()]);
            const std::vector<int>& B = pieces[std::size_t(b)];
            std::size_t at = 0;
            while (B[at] != u) ++at;
            for (std::size_t k = 1; k + 1 < B.size(); ++k) joined.push_back(B[(at + k) % B.size()]);
            points.clear();
            for (const int q : joined) points.push_back(p[std::size_t(q)]);
            if (!is_convex(points, normal)) continue;
            pieces[a] = joined;
            pieces.erase(pieces.begin() + b);
            if (std::size_t(b) < a) --a;
            i = std::size_t(-1);  // look at the joined piece's edges again
        }
    }
    return pieces;
}

SliverSplit split_sliver(const DVec3& p0, const DVec3& p1, const DVec3& p2, float max_aspect) {
    SliverSplit split;
    if (!(max_aspect >= 1.0f)) return split;
    const DVec3 p[3] = {p0, p1, p2};
    int k = 0;  // longest edge p[k] -> p[k + 1]
    for (int i = 1; i < 3; ++i)
        if (glm::length(p[(i + 1) % 3] - p[i]) > glm::length(p[(k + 1) % 3] - p[k])) k = i;
    const DVec3 &a = p[k], &b = p[(k + 1) % 3], &r = p[(k + 2) % 3];
    const double length = glm::length(b - a), along = glm::dot(r - a, b - a) / length;
    const DVec3 foot = a + (b - a) * (along / length);
    const double height = glm::length(r - foot);
    if (!(length > max_aspect * height)) return split;
    split.sliver = true;
    if (along <= height)
        split.apex = (k + 1) % 3;  // short edge r-a: apex b
    else if (length - along <= height)
        split.apex = k;  // short edge b-r: apex a
    else
        split.at_foot = true, split.longest = k, split.foot = foot;
    return split;
}

bool clip_segment(const std::vector<DVec3>& part, const DVec3& normal, double tolerance, DVec3& a, DVec3& b) {
    double t0 = 0.0, t1 = 1.0;
    const DVec3 d = b - a;
    for (std::size_t k = 0; k < part.size(); ++k) {
        const DVec3 inward = glm::cross(normal, part[(k + 1) % part.size()] - part[k]);
        const double at_a = glm::dot(inward, a - part[k]), rate = glm::dot(inward, d);
        if (rate == 0.0) {
            if (at_a < 0.0) return false;
        } else if (rate > 0.0) {
            t0 = std::max(t0, -at_a / rate);
        } else {
            t1 = std::min(t1, -at_a / rate);
        }
    }
    if (!(t1 > t0) || (t1 - t0) * glm::length(d) <= tolerance) return false;
    const DVec3 from = a;
    a = from + d * t0;
    b = from + d * t1;
    return true;
}

}  // namespace radiosity::detail
