/// @file stratified.h
/// @brief Deterministic stratified samples: points on a triangle or quad, cosine-weighted
/// directions on a hemisphere, points in a cube (internal; the hierarchy's visibility rays, the final
/// gather, the zones' rays).
#pragma once

#include "common/types.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdint>

namespace radiosity::detail {

/// The next jitter in [0, 1) of a linear congruential sequence (advances `seed`).
inline float next_jitter(uint32_t& seed) {
    seed = seed * 1664525U + 1013904223U;
    return float(seed >> 8) / 16777216.0f;
}

/// A hash of two integers, for seeds that depend on what is sampled and not on thread order.
inline uint32_t mix_seed(uint32_t a, uint32_t b) {
    uint32_t h = a * 2654435761U ^ (b + 0x9E3779B9U + (a << 6) + (a >> 2));
    h ^= h >> 16;
    h *= 0x85EBCA6BU;
    h ^= h >> 13;
    return h;
}

/// `grid` x `grid` points on a triangle (count 3) or bilinear quad (count 4) with corners `c`,
/// one jittered point per cell of its parameter square (triangles by the square-root warp).
inline void stratified_points(const Vec3* c, int count, int grid, uint32_t seed, Vec3* points) {
    for (int i = 0; i < grid * grid; ++i) {
        const float ju = next_jitter(seed);
        const float jv = next_jitter(seed);
        const float u = (float(i % grid) + ju) / grid, v = (float(i / grid) + jv) / grid;
        if (count == 3) {
            const float su = std::sqrt(u);
            points[i] = (1.0f - su) * c[0] + su * (1.0f - v) * c[1] + su * v * c[2];
        } else {
            points[i] = (1 - u) * (1 - v) * c[0] + u * (1 - v) * c[1] + u * v * c[2] + (1 - u) * v * c[3];
        }
    }
}

/// Point n of Roberts' R3 sequence in [0, 1)^3: well spread for any run of consecutive n, so
/// points n .. n + m of it cover a cube evenly for every m.
inline Vec3 r3_point(std::size_t n) {
    constexpr double g = 1.2207440846057594754;  // the plastic number: x^4 = x + 1
    constexpr double a1 = 1.0 / g, a2 = 1.0 / (g * g), a3 = 1.0 / (g * g * g);
    const double i = double(n);
    return Vec3(float(std::fmod(0.5 + a1 * i, 1.0)), float(std::fmod(0.5 + a2 * i, 1.0)),
                float(std::fmod(0.5 + a3 * i, 1.0)));
}

/// Two unit tangents completing the unit normal `n` to a right-handed frame.
inline void tangent_frame(const glm::dvec3& n, glm::dvec3& t, glm::dvec3& b) {
    const glm::dvec3 a = std::abs(n.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    t = glm::normalize(glm::cross(a, n));
    b = glm::cross(n, t);
}

/// Cosine-weighted direction (pdf cos / pi) about unit normal `n` for the point (u, v) of the unit
/// square (Malley: a uniform point on the disc lifted onto the hemisphere).
inline glm::dvec3 cosine_direction(const glm::dvec3& n, const glm::dvec3& t, const glm::dvec3& b, double u, double v) {
    const double r = std::sqrt(u), phi = 2.0 * M_PI * v;
    return r * std::cos(phi) * t + r * std::sin(phi) * b + std::sqrt(std::max(0.0, 1.0 - u)) * n;
}

}  // namespace radiosity::detail
