/// @file conform.cpp
/// @brief Leaves split into few well-shaped elements (hierarchy/conform.h).
#include "hierarchy/conform.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace radiosity::hr {
namespace {

constexpr int32_t kNone = std::numeric_limits<int32_t>::max();

}  // namespace

// Dynamic programming over the convex polygon's chords: the sub-polygon i..j takes one element
// on its chord and the best splits of the sub-polygons that element leaves. Quads are tried
// only with a side on the polygon's boundary (k = i + 1, l = k + 1 or l = j - 1), which keeps it
// cubic in the points (all quads would make it quartic).
void LeafSplitter::split(const std::vector<Vec3>& points, const std::vector<uint8_t>& edges,
                         std::vector<std::array<int32_t, 4>>& elements) {
    n_ = points.size();
    edges_ = &edges;
    directions_.resize(n_ * n_);
    for (std::size_t a = 0; a < n_; ++a)
        for (std::size_t b = 0; b < n_; ++b)
            if (a != b) directions_[a * n_ + b] = glm::normalize(points[b] - points[a]);
    cells_.assign(n_ * n_, Cell{kNone, 0.0f, -1, -1});
    for (std::size_t i = 0; i + 1 < n_; ++i) cell(i, i + 1) = Cell{0, 0.0f, -1, -1};
    for (std::size_t length = 2; length < n_; ++length)
        for (std::size_t i = 0; i + length < n_; ++i) {
            const std::size_t j = i + length;
            Cell best{kNone, 0.0f, -1, -1};
            for (auto k = int32_t(i + 1); k < int32_t(j); ++k) consider(i, j, k, -1, best);
            for (auto k = int32_t(i + 1); k + 1 < int32_t(j); ++k) {
                consider(i, j, k, k + 1, best);
                consider(i, j, int32_t(i + 1), k + 1, best);
                consider(i, j, k, int32_t(j - 1), best);
            }
            cell(i, j) = best;
        }
    // A convex polygon with three corners not on one line always has a triangulation without
    // degenerate triangles (clip the corners next to flat points first), so the root has a split.
    pending_.assign(1, {0, int32_t(n_ - 1)});
    while (!pending_.empty()) {
        const auto [i, j] = pending_.back();
        pending_.pop_back();
        if (j == i + 1) continue;
        const Cell& c = cell(i, j);
        elements.push_back({i, c.k, c.l < 0 ? j : c.l, c.l < 0 ? -1 : j});
        pending_.push_back({i, c.k});
        pending_.push_back({c.k, c.l < 0 ? j : c.l});
        if (c.l >= 0) pending_.push_back({c.l, j});
    }
}

/// The element i, k, (l,) j on the chord of i..j, if it and the sub-polygons it leaves split
/// without degenerate elements, into `best` when it has fewer elements or better corners.
void LeafSplitter::consider(std::size_t i, std::size_t j, int32_t k, int32_t l, Cell& best) {
    const auto a = int32_t(i), d = int32_t(j);
    if (l < 0 ? on_one_line(a, k, d)
              : on_one_line(a, k, l) || on_one_line(k, l, d) || on_one_line(l, d, a) || on_one_line(d, a, k))
        return;
    const Cell* parts[3] = {&cell(i, std::size_t(k)), &cell(std::size_t(k), std::size_t(l < 0 ? d : l)),
                            l < 0 ? nullptr : &cell(std::size_t(l), j)};
    int32_t count = 1;
    float worst = 0.0f;
    for (const Cell* part : parts) {
        if (!part) continue;
        if (part->count == kNone) return;
        count += part->count;
        worst = std::max(worst, part->worst);
    }
    if (count > best.count) return;
    if (l < 0)
        worst = std::max({worst, corner_cos(d, a, k), corner_cos(a, k, d), corner_cos(k, d, a)});
    else
        worst = std::max({worst, corner_cos(d, a, k), corner_cos(a, k, l), corner_cos(k, l, d), corner_cos(l, d, a)});
    if (count < best.count || worst < best.worst) best = Cell{count, worst, k, l};
}

/// |cos| of the angle at `at` between the sides to `before` and `after`: near 1 for corners near
/// 0 or 180 degrees, the two ways an element degenerates.
float LeafSplitter::corner_cos(int32_t before, int32_t at, int32_t after) const {
    return std::abs(glm::dot(directions_[std::size_t(at) * n_ + std::size_t(before)],
                             directions_[std::size_t(at) * n_ + std::size_t(after)]));
}

}  // namespace radiosity::hr
