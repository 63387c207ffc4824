/// @file corner_wedges.cpp
/// @brief Tables of the light around the element corners on seams (corner_wedges.h).
#include "output/corner_wedges.h"

#include "output/corner_approach.h"
#include "output/corner_blend.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace radiosity::detail {
namespace {

/// Corner k's distances (a, b) along its two edges (to corner k + 1 and to corner k - 1) of the
/// point at the ray tracer's (u, v) in element e, whose corners blend as corner_weights says.
std::pair<double, double> along_edges(bool triangle, int k, double u, double v) {
    if (triangle) {
        switch (k) {
            case 0:
                return {u, v};
            case 1:
                return {v, 1.0 - u - v};
            default:
                return {1.0 - u - v, u};
        }
    }
    switch (k) {
        case 0:
            return {u, v};
        case 1:
            return {v, 1.0 - u};
        case 2:
            return {1.0 - u, 1.0 - v};
        default:
            return {1.0 - v, u};
    }
}

}  // namespace

Vec3 CornerWedges::point_at(const Elements& elements, std::size_t e, int k, double s) const {
    const int count = elements.corner_count(e);
    const Vec3 corner = elements.vertices[std::size_t(elements.corners[e][k])];
    const Vec3 next = elements.vertices[std::size_t(elements.corners[e][(k + 1) % count])] - corner;
    const Vec3 previous = elements.vertices[std::size_t(elements.corners[e][(k + count - 1) % count])] - corner;
    const double angle = s * M_PI / 2.0;
    const Vec3 direction = glm::normalize(float(std::cos(angle)) * next + float(std::sin(angle)) * previous);
    // As far as Cycles bakes a corner from its vertex (corner_approach.h), so that the table holds
    // the light where the rays of a corner beside it land; at most a tenth of the shorter edge.
    const float hair =
        std::min(bake_offset(corner, scene_size_), 0.1f * std::min(glm::length(next), glm::length(previous)));
    return corner + hair * direction;
}

void CornerWedges::fill_table(const Elements& elements, std::size_t slot, const FillTable& fill) {
    const std::size_t e = slot / 4;
    const int k = int(slot % 4);
    std::array<Vec3, kBins> points;
    for (int i = 0; i < kBins; ++i) points[std::size_t(i)] = point_at(elements, e, k, (i + 0.5) / kBins);
    fill(e, k, points.data(), &values_[std::size_t(table_of_slot_[slot])]);
}

template <typename Visit>
void CornerWedges::visit_terms(const Elements& elements, std::size_t element, float u, float v,
                               const Visit& visit) const {
    const bool triangle = elements.is_triangle(element);
    const double uu = std::clamp(double(u), 0.0, 1.0), vv = std::clamp(double(v), 0.0, 1.0);
    const std::array<double, 4> weight = corner_weights(elements, element, u, v);
    for (int k = 0; k < elements.corner_count(element); ++k) {
        const int32_t first = table_of_slot_[4 * element + std::size_t(k)];
        if (first < 0) continue;
        const auto [a, b] = along_edges(triangle, k, uu, vv);
        if (!(a + b > 0.0)) continue;  // at the vertex itself: its own value
        // Linear between the bins' centres, the end bins' values out to the edges.
        const double position = std::atan2(b, a) / (M_PI / 2.0) * kBins - 0.5;
        const int low = std::clamp(int(std::floor(position)), 0, kBins - 1);
        const int high = std::min(low + 1, kBins - 1);
        const double t = std::clamp(position - low, 0.0, 1.0);
        visit(first + low, weight[std::size_t(k)] * (1.0 - t), first + high, weight[std::size_t(k)] * t);
    }
}

Rgb CornerWedges::correction(const Elements& elements, std::size_t element, float u, float v) const {
    Rgb sum(0.0);
    visit_terms(elements, element, u, v, [&](int32_t low, double low_weight, int32_t high, double high_weight) {
        sum += low_weight * values_[std::size_t(low)] + high_weight * values_[std::size_t(high)];
    });
    return elements.reflectance[element] * sum;
}

void CornerWedges::terms(const Elements& elements, std::size_t element, float u, float v,
                         std::vector<std::pair<int32_t, double>>& terms) const {
    visit_terms(elements, element, u, v, [&](int32_t low, double low_weight, int32_t high, double high_weight) {
        terms.emplace_back(low, low_weight);
        terms.emplace_back(high, high_weight);
    });
}

}  // namespace radiosity::detail
