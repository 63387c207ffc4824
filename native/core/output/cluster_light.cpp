/// @file cluster_light.cpp
/// @brief The output elements' light from a solve over merged elements (cluster_light.h).
#include "output/cluster_light.h"

#include "output/interpolation.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat2x2.hpp>

#include <algorithm>
#include <array>
#include <memory>

namespace radiosity::detail {
namespace {

using DVec3 = glm::dvec3;

/// The corner weights of point x in solve element s: barycentric over a triangle; over a quad the
/// bilinear parameters of x (Newton's method from the centre: the quads are convex and planar),
/// clamped to the quad.
std::array<double, 4> corner_weights(const Elements& solve, std::size_t s, const Vec3& x) {
    auto corner = [&](int k) { return DVec3(solve.vertices[solve.corners[s][k]]); };
    const DVec3 p(x), a = corner(0), b = corner(1), c = corner(2);
    if (solve.is_triangle(s)) {
        const DVec3 n = glm::cross(b - a, c - a);
        const double whole = glm::dot(n, n);
        const double wb = glm::dot(glm::cross(p - a, c - a), n) / whole;
        const double wc = glm::dot(glm::cross(b - a, p - a), n) / whole;
        return {1.0 - wb - wc, wb, wc, 0.0};
    }
    const DVec3 d = corner(3);
    double u = 0.5, v = 0.5;
    for (int step = 0; step < 8; ++step) {
        const DVec3 at = (1 - u) * (1 - v) * a + u * (1 - v) * b + u * v * c + (1 - u) * v * d;
        const DVec3 du = (1 - v) * (b - a) + v * (c - d), dv = (1 - u) * (d - a) + u * (c - b);
        const glm::dmat2 normal_matrix(glm::dot(du, du), glm::dot(du, dv), glm::dot(du, dv), glm::dot(dv, dv));
        const glm::dvec2 step_uv = glm::inverse(normal_matrix) * glm::dvec2(glm::dot(du, p - at), glm::dot(dv, p - at));
        u += step_uv.x;
        v += step_uv.y;
    }
    u = std::clamp(u, 0.0, 1.0);
    v = std::clamp(v, 0.0, 1.0);
    return {(1 - u) * (1 - v), u * (1 - v), u * v, (1 - u) * v};
}

/// Shifts each merged cluster's members so that their mean by area is the cluster's radiance.
void keep_cluster_means(const Elements& output, const Clusters& clusters, const std::vector<Rgb>& radiance,
                        std::vector<Rgb>& inherited) {
    const std::size_t count = clusters.elements.size();
    std::vector<Rgb> sum(count, Rgb(0.0));
    std::vector<double> area(count, 0.0);
    for (std::size_t e = 0; e < output.size(); ++e) {
        const std::size_t s = std::size_t(clusters.of_element[e]);
        sum[s] += double(output.area[e]) * inherited[e];
        area[s] += double(output.area[e]);
    }
    for (std::size_t e = 0; e < output.size(); ++e) {
        const std::size_t s = std::size_t(clusters.of_element[e]);
        if (!(area[s] > 0.0)) continue;
        inherited[e] = glm::max(inherited[e] + radiance[s] - sum[s] / area[s], Rgb(0.0));
    }
}

}  // namespace

std::vector<Rgb> inherited_radiance(const Elements& output, const Clusters& clusters, const std::vector<Rgb>& radiance,
                                    const int32_t* material, float hard_edge_angle) {
    if (!clusters.merged()) return radiance;
    const Elements& solve = clusters.elements;
    std::vector<int32_t> members(solve.size(), 0);
    for (const int32_t s : clusters.of_element) ++members[std::size_t(s)];
    const CornerColors corners = interpolate_corners(solve, radiance, material, hard_edge_angle);
    std::vector<Rgb> inherited(output.size());
    for (std::size_t e = 0; e < output.size(); ++e) {
        const std::size_t s = std::size_t(clusters.of_element[e]);
        if (members[s] == 1) {
            inherited[e] = radiance[s];
            continue;
        }
        const std::array<double, 4> w = corner_weights(solve, s, output.centre[e]);
        Rgb value(0.0);
        for (int k = 0; k < solve.corner_count(s); ++k)
            value += w[std::size_t(k)] * corners.element_corner[4 * s + std::size_t(k)];
        inherited[e] = value;
    }
    keep_cluster_means(output, clusters, radiance, inherited);
    return inherited;
}

std::vector<Rgb> inherited_emission(const Clusters& clusters, const std::vector<Rgb>& emitted,
                                    const std::vector<Rgb>& solve_emission, const std::vector<Rgb>& solve_emitted) {
    if (!clusters.merged()) return solve_emission;
    std::vector<Rgb> emission = emitted;
    for (std::size_t e = 0; e < emission.size(); ++e) {
        const std::size_t s = std::size_t(clusters.of_element[e]);
        emission[e] += solve_emission[s] - solve_emitted[s];
    }
    return emission;
}

ProgressFn output_progress(const Clusters& clusters, const ProgressFn& progress) {
    if (!clusters.merged() || !progress) return progress;
    auto output = std::make_shared<std::vector<Rgb>>(clusters.of_element.size());
    return [&clusters, progress, output](const Progress& p) {
        if (p.radiance == nullptr || p.element_count != clusters.elements.size()) return progress(p);
        for (std::size_t e = 0; e < output->size(); ++e) (*output)[e] = p.radiance[clusters.of_element[e]];
        Progress report = p;
        report.radiance = output->data();
        report.element_count = output->size();
        return progress(report);
    };
}

}  // namespace radiosity::detail
