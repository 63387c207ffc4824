/// @file corner_blend.h
/// @brief How a point of an element blends its corners' values, and the bubble over it (internal;
/// the final gather).
///
/// The field the gather's rays read holds 4 slots an element (slot 4 e + k: corner k's value) and,
/// where it carries the lamps' bubbles (lamp_bubbles.h), after them one amplitude an element
/// (bubble_slot). A point's value is its corners' blend plus, with bubbles, the element's bubble
/// there times that amplitude.
#pragma once

#include "geometry/scene.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

namespace radiosity::detail {

/// Each corner's weight at the ray tracer's parameters (u, v) of a point in element e, clamped to
/// it: (1 - u - v, u, v) on a triangle, bilinear on a quad ((0, 0) at corner 0, (1, 0) at corner 1).
inline std::array<double, 4> corner_weights(const Elements& elements, std::size_t e, float u, float v) {
    const double a = std::clamp(double(u), 0.0, 1.0), b = std::clamp(double(v), 0.0, 1.0);
    if (elements.is_triangle(e)) return {1.0 - a - b, a, b, 0.0};
    return {(1.0 - a) * (1.0 - b), a * (1.0 - b), a * b, (1.0 - a) * b};
}

/// Element e's corner values `c` (4 an element, as CornerColors::element_corner) blended at (u, v).
inline Rgb blend_corners(const Elements& elements, std::size_t e, const Rgb* c, float u, float v) {
    const std::array<double, 4> w = corner_weights(elements, e, u, v);
    Rgb sum = w[0] * c[0];
    for (int k = 1; k < elements.corner_count(e); ++k) sum += w[std::size_t(k)] * c[k];
    return sum;
}

/// The bubble of element e at (u, v), read as corner_weights reads them: 0 on the edges, 1 at the
/// centre (27 l0 l1 l2 on a triangle, 16 u (1 - u) v (1 - v) on a quad).
inline double element_bubble(const Elements& elements, std::size_t e, float u, float v) {
    const double a = std::clamp(double(u), 0.0, 1.0), b = std::clamp(double(v), 0.0, 1.0);
    if (elements.is_triangle(e)) return 27.0 * std::max(0.0, 1.0 - a - b) * a * b;
    return 16.0 * a * (1.0 - a) * b * (1.0 - b);
}

/// Whether `field` carries a bubble amplitude per element after its corner slots.
inline bool has_bubbles(const std::vector<Rgb>& field, const Elements& elements) {
    return field.size() > 4 * elements.size();
}

/// The field slot of element e's bubble amplitude.
inline std::size_t bubble_slot(const Elements& elements, std::size_t e) { return 4 * elements.size() + e; }

}  // namespace radiosity::detail
