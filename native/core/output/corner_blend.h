/// @file corner_blend.h
/// @brief How a point of an element blends its corners' values (internal; the final gather).
#pragma once

#include "geometry/scene.h"

#include <algorithm>
#include <array>

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

}  // namespace radiosity::detail
