/// @file test_world.cpp
/// @brief The world's light against closed forms: a lone plane under a uniform sky, a floor under
/// a roof (Howell's parallel squares), a room's points seeing the sky through a window (Lambert's
/// point-to-polygon factor), one lit pixel of the map, and a small sun disc that only importance
/// sampling finds with few rays.
#include "bake/bake.h"
#include "hierarchy/hierarchy.h"
#include "testing/test_util.h"
#include "transport/near_field.h"
#include "transport/world.h"
#include "transport/world_light.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace radiosity {
namespace {

/// Opposed unit squares one apart: area-to-area and centre-point form factors (Howell's catalogue).
constexpr double kParallelArea = 0.19982, kParallelCentre = 0.239456;

/// A lone upward plane: a sky of radiance W gives E = pi W, so L = rho W, exactly.
TEST(World, LonePlaneUnderUniformSkyIsRhoTimesSkyExactly) {
    test::SceneArrays s;
    const Rgb rho(0.2, 0.5, 0.8), W(0.3, 0.6, 1.2);
    s.add_quad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, rho);
    for (const bool gather : {false, true}) {
        BakeSettings settings;
        settings.element_size = 0.5f;
        settings.world = WorldLight::uniform(W, 64);
        settings.final_gather.enabled = gather;
        const BakeResult r = bake(s.input(), settings);
        ASSERT_EQ(r.build.elements.size(), 16u);
        const Rgb stored = r.build.elements.reflectance[0];  // rho as the float input holds it
        for (const Rgb& L : r.solve.radiance)
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(L[c], stored[c] * W[c], 1e-12 * W[c]);
        for (const Rgb& L : r.colors.input_corner)
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(L[c], stored[c] * W[c], 1e-6 * W[c]) << "gather " << gather;
    }
}

/// A floor under a black roof of the same unit square, one apart: it sees the sky through
/// everything but the roof, E = pi W (1 - F), with F the area-to-area factor for the floor's mean
/// and the centre-point factor at its centre. The floor's mean from 4,096 rays is within 0.43% RMS
/// of it over 30 seeds (0.57% with each point's rays stratified on their own), and their mean
/// within 0.2%: the estimate is unbiased.
TEST(World, FloorUnderRoofMissesTheRoofsFormFactor) {
    const WorldLight world = WorldLight::uniform(Rgb(1.0), 4096);
    const double truth = M_PI * (1.0 - kParallelArea);
    double sum = 0.0, error2 = 0.0;
    const int seeds = 30;
    for (int seed = 0; seed < seeds; ++seed) {
        // Small quads far below the floor come first, so that the floor's element, and its seed, differ.
        test::SceneArrays s;
        for (int k = 0; k < seed; ++k)
            s.add_quad({100.0f + k, 0, -100}, {100.1f + k, 0, -100}, {100.1f + k, 0.1f, -100}, {100.0f + k, 0.1f, -100},
                       Rgb(0.5));
        s.add_quad({0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}, Rgb(0.0));  // the roof, facing down
        s.add_quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, Rgb(0.5));  // the floor, facing up
        const Elements e = build_elements(s.input(), 0.0f, ElementLimits()).elements;
        ASSERT_EQ(e.size(), std::size_t(seed + 2));
        const double E = world_irradiance(e, world).back().g;
        sum += E;
        error2 += (E / truth - 1.0) * (E / truth - 1.0);
    }
    EXPECT_NEAR(sum / seeds, truth, 0.002 * truth);
    EXPECT_LT(std::sqrt(error2 / seeds), 0.005);

    const test::SceneArrays s = test::opposed_unit_squares(1.0f, Rgb(0.5), Rgb(0.0));
    const Elements e = build_elements(s.input(), 0.0f, ElementLimits()).elements;
    const std::vector<Rgb> E = world_irradiance_at(e, world, {Vec3(0.5f, 0.5f, 0.0f)}, {Vec3(0, 0, 1)});
    EXPECT_NEAR(E[0].g, M_PI * (1.0 - kParallelCentre), 0.002 * M_PI * (1.0 - kParallelCentre));
}

/// A 2 m room whose x = 2 wall has a 0.8 m window (blender_tests/world_scenes.py's room), under a
/// uniform sky of radiance 1: from a point on the floor, the ceiling or the wall facing the window
/// the sky is the whole window, so E = pi F with F Lambert's factor from the point to the window
/// (what an area lamp filling it gives).
struct WindowRoom {
    test::SceneArrays s;
    const float y0 = 0.6f, y1 = 1.4f, z0 = 0.8f, z1 = 1.6f;  // the window in x = 2
    const glm::dvec3 window[4] = {{2, y0, z0}, {2, y0, z1}, {2, y1, z1}, {2, y1, z0}};

    WindowRoom() {
        const Rgb rho(0.5);
        s.add_quad({0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, rho);  // floor, +z
        s.add_quad({0, 0, 2}, {0, 2, 2}, {2, 2, 2}, {2, 0, 2}, rho);  // ceiling, -z
        s.add_quad({0, 0, 0}, {0, 2, 0}, {0, 2, 2}, {0, 0, 2}, rho);  // x = 0, +x
        s.add_quad({0, 0, 0}, {0, 0, 2}, {2, 0, 2}, {2, 0, 0}, rho);  // y = 0, +y
        s.add_quad({0, 2, 0}, {2, 2, 0}, {2, 2, 2}, {0, 2, 2}, rho);  // y = 2, -y
        wall(0, 2, 0, z0);
        wall(0, 2, z1, 2);
        wall(0, y0, z0, z1);
        wall(y1, 2, z0, z1);
    }
    void wall(float ya, float yb, float za, float zb) {  // a piece of x = 2, facing -x
        s.add_quad({2, ya, za}, {2, ya, zb}, {2, yb, zb}, {2, yb, za}, Rgb(0.5));
    }
    /// The irradiance at x facing unit n: pi times Lambert's factor to the window.
    double truth(const Vec3& x, const Vec3& n) const {
        return M_PI * point_to_polygon(glm::dvec3(x), glm::dvec3(n), window, 4, glm::dvec3(-1, 0, 0));
    }
    /// Whether an element of the floor, the ceiling or the x = 0 wall, which see the whole window.
    static bool sees_the_whole_window(const Vec3& n) { return std::abs(n.z) > 0.5f || n.x > 0.5f; }
};

/// At WorldLight::point_samples rays a point, spent where the window's edges are (world_point.cpp):
/// 0.29% RMS over 192 points; plain stratified rays had 1.28% at the 8,192 rays a point they had.
TEST(World, PointsSeeTheSkyThroughAWindowAsLambertsFactor) {
    const WindowRoom room;
    const Elements e = build_elements(room.s.input(), 0.0f, ElementLimits()).elements;
    std::vector<Vec3> points, normals;
    for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 8; ++j) {
            const float a = 0.125f + 0.25f * i, b = 0.125f + 0.25f * j;
            points.insert(points.end(), {Vec3(a, b, 0), Vec3(a, b, 2), Vec3(0, a, b)});
            normals.insert(normals.end(), {Vec3(0, 0, 1), Vec3(0, 0, -1), Vec3(1, 0, 0)});
        }
    const std::vector<Rgb> E = world_irradiance_at(e, WorldLight::uniform(Rgb(1.0)), points, normals);
    double error2 = 0.0, truth2 = 0.0;
    for (std::size_t k = 0; k < points.size(); ++k) {
        const double truth = room.truth(points[k], normals[k]);
        error2 += (E[k].g - truth) * (E[k].g - truth);
        truth2 += truth * truth;
    }
    EXPECT_LT(std::sqrt(error2 / truth2), 0.004);
}

/// Each element's mean over it, from WorldLight::samples rays padded across its points
/// (padded_samples): 7.6% RMS over the 300 elements of 0.2 m that see the whole window, against
/// 12.8% for each point's rays stratified on their own; the truth is the mean of 24 x 24 points'.
TEST(World, ElementsSeeTheSkyThroughAWindowAsLambertsFactor) {
    const WindowRoom room;
    const Elements e = build_elements(room.s.input(), 0.2f, ElementLimits()).elements;
    const std::vector<Rgb> E = world_irradiance(e, WorldLight::uniform(Rgb(1.0), WorldLight().samples));
    double error2 = 0.0, truth2 = 0.0;
    int seen = 0;
    for (std::size_t k = 0; k < e.size(); ++k) {
        if (!WindowRoom::sees_the_whole_window(e.normal[k])) continue;
        const Vec3* c[4];
        for (int q = 0; q < 4; ++q) c[q] = &e.vertices[std::size_t(e.corners[k][q])];
        double truth = 0.0;
        const int grid = 24;
        for (int a = 0; a < grid; ++a)
            for (int b = 0; b < grid; ++b) {
                const float u = (a + 0.5f) / grid, v = (b + 0.5f) / grid;
                truth += room.truth(
                    (1 - u) * (1 - v) * *c[0] + u * (1 - v) * *c[1] + u * v * *c[2] + (1 - u) * v * *c[3], e.normal[k]);
            }
        truth /= grid * grid;
        error2 += (E[k].g - truth) * (E[k].g - truth);
        truth2 += truth * truth;
        ++seen;
    }
    ASSERT_EQ(seen, 300);
    EXPECT_LT(std::sqrt(error2 / truth2), 0.09);
}

/// The hierarchical bake: the same lone plane, exact at every corner and leaf.
TEST(World, HierarchicalLonePlaneIsRhoTimesSkyExactly) {
    test::SceneArrays s;
    const Rgb W(0.3, 0.6, 1.2);
    s.add_quad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, Rgb(0.5));
    HierarchySettings settings;
    settings.world = WorldLight::uniform(W, 64);
    const HierarchyResult r = bake_hierarchical(s.input(), settings);
    for (const Rgb& L : r.output_radiance)
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(L[c], 0.5 * W[c], 1e-12 * W[c]);
    ASSERT_EQ(r.colors.input_corner.size(), 4u);
    for (const Rgb& L : r.colors.input_corner)
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(L[c], 0.5 * W[c], 1e-6 * W[c]);
}

/// The hierarchical bake's corners show the world's light as it is there: a floor corner under a
/// black roof (the same unit square, one above) misses the roof's factor from a point under a
/// rectangle's corner, (1 / pi) X / sqrt(1 + X^2) atan(Y / sqrt(1 + X^2)) doubled for X = Y = 1.
TEST(World, HierarchicalCornersShowTheWorldAsItIsThere) {
    const test::SceneArrays s = test::opposed_unit_squares(1.0f, Rgb(0.5), Rgb(0.0));
    HierarchySettings settings;
    settings.world = WorldLight::uniform(Rgb(1.0));
    settings.world.point_samples = 16384;
    const HierarchyResult r = bake_hierarchical(s.input(), settings);
    const double corner_factor = 2.0 / (2.0 * M_PI) * std::sqrt(0.5) * std::atan(std::sqrt(0.5));
    ASSERT_EQ(r.colors.input_corner.size(), 8u);
    for (std::size_t k = 4; k < 8; ++k)  // the floor's corners
        EXPECT_NEAR(r.colors.input_corner[k].g, 0.5 * (1.0 - corner_factor), 0.003 * 0.5) << k;
}

/// A map black but for one pixel: u in [1/4, 3/8) (azimuth 45 to 90 degrees, from +x towards +y),
/// v in [1/2, 3/4) (from the horizon to 45 degrees up), of radiance 1. Cycles' convention puts
/// it towards +y, +x and up; a plane facing +y receives the integral of sin(theta) sin(phi) over
/// it: (pi / 8 + 1 / 4) cos(pi / 4).
TEST(World, OnePixelLightsTheDirectionsOfCyclesConvention) {
    WorldLight world;
    world.width = 8;
    world.height = 4;
    world.radiance.assign(32, Rgb(0.0));
    world.radiance[2 * 8 + 2] = Rgb(1.0);
    world.point_samples = 4096;
    test::SceneArrays s;  // a speck far below, so nothing occludes
    s.add_quad({-0.01f, -0.01f, -5}, {0.01f, -0.01f, -5}, {0.01f, 0.01f, -5}, {-0.01f, 0.01f, -5}, Rgb(0.5));
    const Elements e = build_elements(s.input(), 0.0f, ElementLimits()).elements;
    const std::vector<Vec3> normals{{0, 1, 0}, {0, -1, 0}, {1, 0, 0}, {-1, 0, 0}, {0, 0, 1}, {0, 0, -1}};
    const std::vector<Rgb> E = world_irradiance_at(e, world, std::vector<Vec3>(6, Vec3(0.0f)), normals);
    const double towards_y = (M_PI / 8 + 0.25) * std::cos(M_PI / 4);
    EXPECT_NEAR(E[0].r, towards_y, 0.005 * towards_y);
    EXPECT_EQ(E[1].r, 0.0);
    EXPECT_GT(E[2].r, 0.1);
    EXPECT_EQ(E[3].r, 0.0);
    EXPECT_GT(E[4].r, 0.1);
    EXPECT_EQ(E[5].r, 0.0);
    EXPECT_EQ(world.radiance_from(Vec3(0.3f, 0.9f, 0.3f)), Rgb(1.0));
    EXPECT_EQ(world.radiance_from(Vec3(0.9f, -0.3f, 0.3f)), Rgb(0.0));
}

/// The integral of cos(theta) over a pixel of row j of an equirectangular map (a plane facing up).
double up_irradiance_per_radiance(int width, int height, int j) {
    const double theta_low = M_PI * (1.0 - double(j + 1) / height), theta_high = M_PI * (1.0 - double(j) / height);
    if (theta_low >= M_PI / 2) return 0.0;
    const double high = std::min(theta_high, M_PI / 2);
    return 2.0 * M_PI / width * 0.5 * (std::sin(high) * std::sin(high) - std::sin(theta_low) * std::sin(theta_low));
}

/// A sky of radiance 1 with a sun disc of 0.5 degrees' radius 50 degrees up, 1e6 times brighter:
/// the disc is 2e-5 of the sky's solid angle but gives 95% of the floor's light. 256 rays find it
/// by drawing from the map (0.4% standard deviation over 40 seeds: the map's rays are
/// multi-jittered, so the sun's rows get their share to a ray; 1.3% with rays stratified only by
/// cell); the truth is the map's exact integral, pixel by pixel.
TEST(World, SmallSunDiscIsFoundByImportanceSampling) {
    WorldLight world;
    world.width = 1024;
    world.height = 512;
    world.radiance.assign(std::size_t(world.width) * world.height, Rgb(1.0));
    const double elevation = 50.0 * M_PI / 180.0, azimuth = 30.0 * M_PI / 180.0, radius = 0.5 * M_PI / 180.0;
    const glm::dvec3 sun(std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                         std::sin(elevation));
    double truth = 0.0;
    int lit = 0;
    for (int j = 0; j < world.height; ++j)
        for (int i = 0; i < world.width; ++i) {
            const double u = (i + 0.5) / world.width, v = (j + 0.5) / world.height;
            const double phi = M_PI - 2.0 * M_PI * u, theta = M_PI * (1.0 - v);
            const glm::dvec3 d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
            Rgb& L = world.radiance[std::size_t(j) * world.width + i];
            if (std::acos(std::clamp(glm::dot(d, sun), -1.0, 1.0)) < radius) {
                L = Rgb(1e6);
                ++lit;
            }
            truth += L.r * up_irradiance_per_radiance(world.width, world.height, j);
        }
    ASSERT_GT(lit, 4);
    test::SceneArrays s;
    s.add_quad({-0.01f, -0.01f, -5}, {0.01f, -0.01f, -5}, {0.01f, 0.01f, -5}, {-0.01f, 0.01f, -5}, Rgb(0.5));
    const Elements e = build_elements(s.input(), 0.0f, ElementLimits()).elements;
    world.point_samples = 256;
    const Rgb E = world_irradiance_at(e, world, {Vec3(0.0f)}, {Vec3(0, 0, 1)})[0];
    EXPECT_GT(truth, 10.0 * M_PI);  // the sun dominates
    EXPECT_NEAR(E.r, truth, 0.01 * truth);
}

/// The same scene baked twice gives the same colours (seeds per element and per point).
TEST(World, BakeIsDeterministic) {
    const test::SceneArrays s = test::opposed_unit_squares(0.5f, Rgb(0.5), Rgb(0.0));
    WorldLight world;
    world.width = 16;
    world.height = 8;
    for (int k = 0; k < 128; ++k) world.radiance.push_back(Rgb(0.1 * (k % 7), 0.2, 0.05 * (k % 5)));
    BakeSettings settings;
    settings.element_size = 0.25f;
    settings.world = world;
    settings.final_gather.enabled = true;
    settings.final_gather.rays = 16;
    const BakeResult a = bake(s.input(), settings), b = bake(s.input(), settings);
    EXPECT_EQ(a.colors.input_corner, b.colors.input_corner);
    EXPECT_GT(a.colors.input_corner[4].g, 0.0);
}

/// An element's ray directions, padded across its points: each point has one in each cell of the
/// coarse grid, and all points together one in each cell of the fine grid.
TEST(World, PaddedSamplesStratifyEachPointAndAllTogether) {
    const int points = 64, grid = 4, fine = 32;
    uint32_t seed = 7;
    const std::vector<glm::dvec2> uv = detail::padded_samples(points, grid, seed);
    ASSERT_EQ(uv.size(), std::size_t(points * grid * grid));
    std::vector<int> in_fine(std::size_t(fine * fine), 0);
    for (int k = 0; k < points; ++k) {
        std::vector<int> in_coarse(std::size_t(grid * grid), 0);
        for (int s = 0; s < grid * grid; ++s) {
            const glm::dvec2 p = uv[std::size_t(k * grid * grid + s)];
            ASSERT_TRUE(p.x >= 0.0 && p.x < 1.0 && p.y >= 0.0 && p.y < 1.0);
            ++in_coarse[std::size_t(int(p.y * grid) * grid + int(p.x * grid))];
            ++in_fine[std::size_t(int(p.y * fine) * fine + int(p.x * fine))];
        }
        EXPECT_EQ(in_coarse, std::vector<int>(std::size_t(grid * grid), 1)) << "point " << k;
    }
    EXPECT_EQ(in_fine, std::vector<int>(std::size_t(fine * fine), 1));
}

/// A corner's rays drawn from the map: one in each cell, and one in each of the fine columns and rows.
TEST(World, MultiJitteredSamplesStratifyCellsColumnsAndRows) {
    const int grid = 12, fine = grid * grid;
    uint32_t seed = 11;
    const std::vector<glm::dvec2> uv = detail::multi_jittered_samples(grid, seed);
    ASSERT_EQ(uv.size(), std::size_t(fine));
    std::vector<int> in_cell(std::size_t(fine), 0), in_column(std::size_t(fine), 0), in_row(std::size_t(fine), 0);
    for (const glm::dvec2& p : uv) {
        ASSERT_TRUE(p.x >= 0.0 && p.x < 1.0 && p.y >= 0.0 && p.y < 1.0);
        ++in_cell[std::size_t(int(p.y * grid) * grid + int(p.x * grid))];
        ++in_column[std::size_t(p.x * fine)];
        ++in_row[std::size_t(p.y * fine)];
    }
    const std::vector<int> once(std::size_t(fine), 1);
    EXPECT_EQ(in_cell, once);
    EXPECT_EQ(in_column, once);
    EXPECT_EQ(in_row, once);
}

TEST(World, BadMapIsAnInputError) {
    WorldLight world;
    world.width = 2;
    world.height = 1;
    world.radiance = {Rgb(1.0)};
    EXPECT_THROW(world.check(), InputError);
    world.radiance = {Rgb(1.0), Rgb(-1.0, 0.0, 0.0)};
    EXPECT_THROW(world.check(), InputError);
    world.radiance = {Rgb(1.0), Rgb(NAN)};
    EXPECT_THROW(world.check(), InputError);
}

}  // namespace
}  // namespace radiosity
