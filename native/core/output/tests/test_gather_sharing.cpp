/// @file test_gather_sharing.cpp
/// @brief The final gather sharing indirect light between output corners (FinalGatherSettings::
/// cache_accuracy, irradiance_cache.h) and what it reports it cost (gather_cost.h): a subdivided
/// furnace stays exact, the subdivided Cornell box stays within its gathered-everywhere colours,
/// layers lit by one lamp each add up to the bake lit by both, one thread gives what many do, and
/// the rays each phase traced are the rays the gather casts.
#include "bake/bake.h"

#include "testing/test_util.h"

#include <gtest/gtest.h>

#include <tbb/global_control.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace radiosity {
namespace {

BakeSettings gather_settings(float element_size, double cache_accuracy) {
    BakeSettings s;
    s.element_size = element_size;
    s.resolution = 128;
    s.solve.tolerance = 1e-8;
    s.final_gather.enabled = true;
    s.final_gather.cache_accuracy = cache_accuracy;
    return s;
}

/// `scene` with every quad cut into n x n quads, each with its own vertices (as the scenes are).
test::SceneArrays subdivided(const test::SceneArrays& scene, int n) {
    test::SceneArrays out;
    for (std::size_t f = 0; f + 1 < scene.face_offsets.size(); ++f) {
        std::vector<Vec3> c;
        for (int32_t k = scene.face_offsets[f]; k < scene.face_offsets[f + 1]; ++k) {
            const float* p = &scene.positions[3 * std::size_t(scene.corner_vertices[std::size_t(k)])];
            c.emplace_back(p[0], p[1], p[2]);
        }
        const Rgb rho(scene.reflectance[3 * f], scene.reflectance[3 * f + 1], scene.reflectance[3 * f + 2]);
        const Rgb emitted(scene.emission[3 * f], scene.emission[3 * f + 1], scene.emission[3 * f + 2]);
        if (c.size() != 4) {
            out.add_polygon(c, rho, emitted, scene.material[f]);
            continue;
        }
        auto at = [&](int i, int j) {
            const float s = float(i) / n, t = float(j) / n;
            return (1 - s) * (1 - t) * c[0] + s * (1 - t) * c[1] + s * t * c[2] + (1 - s) * t * c[3];
        };
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j)
                out.add_quad(at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1), rho, emitted, scene.material[f]);
    }
    return out;
}

TEST(GatherSharing, ASubdividedFurnaceStaysExact) {
    // L = E / (1 - rho) everywhere: the records' light and gradients (zero) give it exactly.
    const Rgb rho(0.5, 0.7, 0.9), E(1.0, 0.5, 2.0);
    const test::SceneArrays box = subdivided(test::closed_box(Vec3(1.0f, 1.5f, 0.8f), rho, E), 12);
    const BakeResult r = bake(box.input(), gather_settings(0.3f, 0.3));
    std::printf("furnace: %zu gathered, %zu interpolated, %zu buried\n", r.gathered_points, r.interpolated_points,
                r.buried_points);
    EXPECT_GT(r.interpolated_points, 0u);
    EXPECT_EQ(r.buried_points, 0u);
    EXPECT_LT(test::worst_relative_error(r.colors.input_corner, E / (1.0 - rho)), 1e-3);
}

/// The RMS over corners of each corner's relative difference (green) from `truth`.
double rms_difference(const std::vector<Rgb>& values, const std::vector<Rgb>& truth) {
    double sum = 0.0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (!(truth[i].g > 0.0)) continue;  // the emitter's corners: no light arrives
        const double d = values[i].g / truth[i].g - 1.0;
        sum += d * d;
        ++count;
    }
    return std::sqrt(sum / double(count));
}

TEST(GatherSharing, TheSubdividedCornellBoxKeepsItsGatheredColours) {
    const test::SceneArrays box = subdivided(test::cornell_box(), 12);
    BakeSettings everywhere = gather_settings(0.1f, 0.0);
    everywhere.final_gather.field_rays = 64;
    everywhere.final_gather.rays = 1024;
    BakeSettings shared = everywhere;
    shared.final_gather.cache_accuracy = 0.2;
    const BakeResult a = bake(box.input(), everywhere), b = bake(box.input(), shared);
    const double difference = rms_difference(b.light_colors.input_corner, a.light_colors.input_corner);
    std::printf(
        "Cornell box x12: %zu gathered everywhere, %.2f s; shared %zu gathered, %zu interpolated, %.2f s, "
        "%.2f%% RMS apart\n",
        a.gathered_points, a.seconds_gather, b.gathered_points, b.interpolated_points, b.seconds_gather,
        100 * difference);
    EXPECT_EQ(b.gathered_points + b.interpolated_points + b.buried_points, a.gathered_points + a.buried_points);
    EXPECT_GT(b.interpolated_points, b.gathered_points / 4);
    EXPECT_LT(b.gather_cost.points.rays, a.gather_cost.points.rays / 2);
    EXPECT_LT(difference, 0.01);
}

TEST(GatherSharing, OneThreadGivesTheSameColoursAsMany) {
    // The records are chosen in a fixed order and each point written by one task: no thread count
    // shows in the result.
    const test::SceneArrays box = subdivided(test::cornell_box(), 6);
    BakeSettings settings = gather_settings(0.1f, 0.2);
    settings.final_gather.field_rays = 16;
    settings.final_gather.rays = 256;
    const BakeResult many = bake(box.input(), settings);
    BakeResult one;
    {
        tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
        one = bake(box.input(), settings);
    }
    ASSERT_GT(many.interpolated_points, 0u);
    EXPECT_EQ(one.interpolated_points, many.interpolated_points);
    ASSERT_EQ(one.colors.input_corner.size(), many.colors.input_corner.size());
    EXPECT_EQ(std::memcmp(one.colors.input_corner.data(), many.colors.input_corner.data(),
                          many.colors.input_corner.size() * sizeof(Rgb)),
              0);
}

/// The largest difference between the light of `parts` added up and `whole`'s, relative to the whole.
double worst_sum_difference(const BakeResult& whole, const std::vector<BakeResult>& parts) {
    double worst = 0.0;
    for (std::size_t i = 0; i < whole.light_colors.input_corner.size(); ++i) {
        Rgb sum(0.0);
        for (const BakeResult& part : parts) sum += part.light_colors.input_corner[i];
        const Rgb& total = whole.light_colors.input_corner[i];
        worst = std::max(worst, max_channel(glm::abs(sum - total)) / max_channel(total));
    }
    return worst;
}

TEST(GatherSharing, LayersLitByOneLampEachAddUpToTheWhole) {
    // Which corners gather is decided from geometry only, so sharing keeps the bake linear in its
    // sources: two lamps baked apart add up to both baked together as closely as they do when every
    // corner gathers (the solve's tolerance, the lamps' own sampling), and every layer reads the same
    // records. The box's ceiling light is off in all of them, so that all have the same elements.
    test::SceneArrays box = subdivided(test::cornell_box(), 3);
    for (std::size_t f = 0; f < box.material.size(); ++f)
        if (box.material[f] == 3)
            for (int c = 0; c < 3; ++c) box.emission[3 * f + std::size_t(c)] = 0.0f;
    PointLight high, low;
    high.position = Vec3(0.5f, 0.5f, 0.9f);
    high.intensity = Rgb(3.0, 2.0, 1.0);
    low.position = Vec3(0.1f, 0.3f, 0.4f);
    low.intensity = Rgb(0.5, 1.0, 2.0);
    double worst[2] = {0.0, 0.0};
    for (const int shared : {0, 1}) {
        BakeSettings settings = gather_settings(0.1f, shared ? 0.25 : 0.0);
        settings.final_gather.field_rays = 16;
        settings.final_gather.rays = 256;
        BakeSettings both = settings, first = settings, second = settings;
        both.lights.points = {high, low};
        first.lights.points = {high};
        second.lights.points = {low};
        const BakeResult whole = bake(box.input(), both);
        const std::vector<BakeResult> parts = {bake(box.input(), first), bake(box.input(), second)};
        EXPECT_EQ(whole.interpolated_points > 0, shared == 1);
        for (const BakeResult& part : parts) EXPECT_EQ(part.interpolated_points, whole.interpolated_points);
        worst[shared] = worst_sum_difference(whole, parts);
    }
    std::printf("layers: worst corner %.2e of the whole gathered everywhere, %.2e shared\n", worst[0], worst[1]);
    EXPECT_LE(worst[1], 1.01 * worst[0] + 1e-9);
}

TEST(GatherSharing, EachPhaseReportsTheRaysItTraced) {
    // An open floor of 4 x 4 quads under nothing: no emitter, lamp or world, so every ray is a gather
    // ray or a probe (all miss: none is judged buried, and no point meets a seam).
    test::SceneArrays floor;
    floor.add_quad({0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, Rgb(0.5));
    floor = subdivided(floor, 4);
    BakeSettings settings = gather_settings(0.0f, 0.0);
    settings.final_gather.rays = 64;
    const BakeResult all = bake(floor.input(), settings);
    settings.final_gather.cache_accuracy = 0.5;
    const BakeResult some = bake(floor.input(), settings);
    const std::size_t points = all.gathered_points;
    std::printf("floor: %zu points; shared: %zu gathered, %zu interpolated\n", points, some.gathered_points,
                some.interpolated_points);
    EXPECT_EQ(points, 64u);  // each quad's four corners
    EXPECT_EQ(all.gather_cost.points.rays, 64u * points);
    EXPECT_EQ(all.gather_cost.probes.rays, 0u);
    EXPECT_EQ(all.gather_cost.seams.rays + all.gather_cost.field.rays + all.gather_cost.wedges.rays, 0u);
    EXPECT_EQ(some.gathered_points + some.interpolated_points, points);
    EXPECT_GT(some.interpolated_points, 0u);
    EXPECT_EQ(some.gather_cost.probes.rays, 64u * 25u);  // once at each of the floor's 5 x 5 places
    EXPECT_EQ(some.gather_cost.points.rays, 64u * some.gathered_points);
    EXPECT_EQ(some.gather_cost.rays(), some.gather_cost.probes.rays + some.gather_cost.points.rays);
}

}  // namespace
}  // namespace radiosity
