/// @file test_irradiance_cache.cpp
/// @brief Irradiance caching's parts (irradiance_cache.h): the gradients of a stratified gather
/// against the exact derivatives of a rectangle's point-to-polygon factor, and the records'
/// choice: every point covered, records apart, nothing read across a turn or a step.
#include "output/irradiance_cache.h"

#include "common/stratified.h"
#include "transport/near_field.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <array>
#include <cmath>
#include <cstdio>

namespace radiosity::detail {
namespace {

/// A wall of radiance 1 in the plane x = 1 (facing -x), y in [-0.5, 0.8], z in [0.1, 1.0].
const std::array<glm::dvec3, 4> kWall = {glm::dvec3(1, -0.5, 0.1), glm::dvec3(1, -0.5, 1.0), glm::dvec3(1, 0.8, 1.0),
                                         glm::dvec3(1, 0.8, 0.1)};

/// The wall's exact light at x of normal n (its point-to-polygon factor).
double exact(const glm::dvec3& x, const glm::dvec3& n) {
    return point_to_polygon(x, n, kWall.data(), 4, glm::dvec3(-1, 0, 0));
}

/// The gather's samples at x of normal n, `grid` x `grid` rays traced against the wall analytically.
LightGradients gathered(const glm::dvec3& x, const glm::dvec3& n, int grid, uint32_t seed, double& mean) {
    glm::dvec3 t, b;
    tangent_frame(n, t, b);
    std::vector<double> sample(std::size_t(grid * grid), 0.0), inverse_distance(sample.size(), 0.0);
    mean = 0.0;
    for (int i = 0; i < grid * grid; ++i) {
        const double u = (double(i % grid) + next_jitter(seed)) / grid;
        const double v = (double(i / grid) + next_jitter(seed)) / grid;
        const glm::dvec3 d = cosine_direction(n, t, b, u, v);
        if (!(d.x > 0.0)) continue;
        const double distance = (1.0 - x.x) / d.x;
        const glm::dvec3 hit = x + distance * d;
        if (hit.y < -0.5 || hit.y > 0.8 || hit.z < 0.1 || hit.z > 1.0) continue;
        sample[std::size_t(i)] = 1.0;
        inverse_distance[std::size_t(i)] = 1.0 / distance;
        mean += 1.0;
    }
    mean /= grid * grid;
    const GradientWeights weights = gradient_weights(grid, inverse_distance);
    PlaneGradients sum;
    for (std::size_t i = 0; i < sample.size(); ++i)
        for (std::size_t c = 0; c < 3; ++c) {
            sum.rotation[c] += sample[i] * weights.rotation[i];
            sum.translation[c] += sample[i] * weights.translation[i];
        }
    return sum.in_space(t, b);
}

TEST(IrradianceCache, GradientsMatchTheExactDerivativesOfARectanglesLight) {
    const double h = 1e-4;
    for (const glm::dvec3 n : {glm::dvec3(0, 0, 1), glm::normalize(glm::dvec3(0.3, -0.2, 1.0))}) {
        const glm::dvec3 x(0.2, 0.1, 0.0);
        double mean = 0.0;
        const LightGradients g = gathered(x, n, 64, 7u, mean);
        EXPECT_NEAR(mean, exact(x, n), 0.005);
        // Translation along the surface (two tangents), rotation about two axes in it.
        glm::dvec3 t, b;
        tangent_frame(n, t, b);
        for (const glm::dvec3& along : {t, b}) {
            const double truth = (exact(x + h * along, n) - exact(x - h * along, n)) / (2 * h);
            const double estimate = glm::dot(g.translation[0], along);
            std::printf("translation: exact %.4f, gradient %.4f\n", truth, estimate);
            EXPECT_NEAR(estimate, truth, 0.1 * std::abs(truth) + 0.005);
            // Turning n by a small angle about `axis` = along: n' = n + h (axis x n).
            const glm::dvec3 turned_plus = glm::normalize(n + h * glm::cross(along, n));
            const glm::dvec3 turned_minus = glm::normalize(n - h * glm::cross(along, n));
            const double turn_truth = (exact(x, turned_plus) - exact(x, turned_minus)) / (2 * h);
            const double turn_estimate = glm::dot(g.rotation[0], along);
            std::printf("rotation: exact %.4f, gradient %.4f\n", turn_truth, turn_estimate);
            EXPECT_NEAR(turn_estimate, turn_truth, 0.05 * std::abs(turn_truth) + 0.005);
        }
    }
}

TEST(IrradianceCache, ReadingARecordFollowsTheLightToFirstOrder) {
    // Half a record's validity away, the record read with its gradients is nearer the exact light
    // than the record's own value.
    const glm::dvec3 n(0, 0, 1), x(0.2, 0.1, 0.0), y(0.25, 0.14, 0.0);
    double mean = 0.0;
    const LightGradients g = gathered(x, n, 64, 11u, mean);
    const CachePoint record{x, n, 0.5, false}, point{y, n, 0.5, false};
    const double read = read_record(record, Rgb(exact(x, n)), g, point).r;
    std::printf("record %.4f, read %.4f, exact %.4f\n", exact(x, n), read, exact(y, n));
    EXPECT_LT(std::abs(read - exact(y, n)), 0.2 * std::abs(exact(x, n) - exact(y, n)));
}

/// Points on a grid of `count` x `count` over the unit square in the plane z = `height`.
std::vector<CachePoint> plane(int count, double height, double distance, const glm::dvec3& normal = {0, 0, 1}) {
    std::vector<CachePoint> points;
    for (int i = 0; i < count; ++i)
        for (int j = 0; j < count; ++j)
            points.push_back({glm::dvec3(i / (count - 1.0), j / (count - 1.0), height), normal, distance, false});
    return points;
}

TEST(IrradianceCache, RecordsCoverEveryPointAndLieApart) {
    const double accuracy = 0.2;
    std::vector<CachePoint> points = plane(41, 0.0, 0.5);
    points[0].keep = points[100].keep = true;
    const CachePlan plan = plan_cache(points, accuracy);
    EXPECT_TRUE(plan.record[0] && plan.record[100]);
    const std::size_t records = plan.records();
    std::printf("%zu records of %zu points\n", records, points.size());
    // Each record covers a disc of radius a R = 0.1: the square needs at least 1 / (pi 0.01) of them.
    EXPECT_GE(records, 25u);
    EXPECT_LT(records, points.size() / 4);
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (plan.record[i]) {
            EXPECT_TRUE(plan.from[i].empty());
            for (std::size_t k = 0; k < i; ++k)  // records not kept were not covered when chosen
                if (plan.record[k] && !points[i].keep && !points[k].keep)
                    EXPECT_GE(glm::length(points[i].position - points[k].position), (1.0 - 1e-6) * accuracy * 0.5);
            continue;
        }
        ASSERT_FALSE(plan.from[i].empty()) << i;
        double total = 0.0;
        for (const auto& [r, weight] : plan.from[i]) {
            EXPECT_TRUE(plan.record[std::size_t(r)]);
            EXPECT_LT(glm::length(points[i].position - points[std::size_t(r)].position), accuracy * 0.5);
            EXPECT_GT(weight, 0.0);
            total += weight;
        }
        EXPECT_NEAR(total, 1.0, 1e-12);
    }
    EXPECT_EQ(plan_cache(points, accuracy).record, plan.record);  // a fixed order
    EXPECT_EQ(plan_cache(points, 0.0).records(), points.size());  // no sharing
}

TEST(IrradianceCache, NothingIsReadAcrossATurnOrAStep) {
    // A floor, a wall standing on it (turned a quarter) and a shelf 1 cm over the floor: each reads
    // only its own records, though their points lie within each other's validity.
    std::vector<CachePoint> points = plane(21, 0.0, 0.5);
    for (CachePoint p : plane(21, 0.01, 0.5)) points.push_back(p);
    for (CachePoint p : plane(21, 0.0, 0.5, {1, 0, 0})) {
        p.position = glm::dvec3(0.0, p.position.y, p.position.x);
        points.push_back(p);
    }
    const CachePlan plan = plan_cache(points, 0.3);
    for (std::size_t i = 0; i < points.size(); ++i)
        for (const auto& [r, weight] : plan.from[i]) {
            EXPECT_EQ(std::size_t(r) / 441, i / 441) << i << " reads " << r;
            EXPECT_GT(weight, 0.0);
        }
}

TEST(IrradianceCache, APointNearerToWhatItSeesThanItsNeighbourGathersItself) {
    // A wall under a 2 cm ledge (blender_test_level_features' thin brush, its probes' distances): the
    // point 25 cm under the ledge sees it close (R 1.05 m); the one 50 cm under sees the room (R 1.75 m).
    // Ward's measure lets the lower one's record reach the upper point (0.249 / 1.746 = 0.143 < 0.15),
    // whose light there came out 4.5% over Cycles'; clamped to the upper point's own R plus the 0.249 m
    // between them, it does not (0.249 / 1.301 = 0.191), and each gathers.
    const glm::dvec3 n(0, 1, 0);
    const CachePoint lower{glm::dvec3(0.747, 0.0, 0.993), n, 1.746, false};
    const CachePoint upper{glm::dvec3(0.747, 0.0, 1.242), n, 1.052, false};
    const double accuracy = 0.15;
    EXPECT_NEAR(cache_error(lower, upper), 0.249 / (1.052 + 0.249), 1e-9);
    EXPECT_NEAR(cache_error(upper, lower), 0.249 / 1.052, 1e-9);
    EXPECT_EQ(plan_cache({lower, upper}, accuracy).records(), 2u);
    // Points that see the same distance still share: 20 cm apart on an open wall (R 1.75 m).
    const CachePoint beside{glm::dvec3(0.947, 0.0, 0.993), n, 1.746, false};
    EXPECT_NEAR(cache_error(lower, beside), 0.2 / 1.746, 1e-9);
    EXPECT_EQ(plan_cache({lower, beside}, accuracy).records(), 1u);
}

}  // namespace
}  // namespace radiosity::detail
