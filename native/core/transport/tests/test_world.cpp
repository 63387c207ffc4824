/// @file test_world.cpp
/// @brief The world's light against closed forms: a lone plane under a uniform sky, a floor under
/// a roof (Howell's parallel squares), one lit pixel of the map, and a small sun disc that only
/// importance sampling finds with few rays.
#include "bake/bake.h"
#include "hierarchy/hierarchy.h"
#include "testing/test_util.h"
#include "transport/world.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

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
/// and the centre-point factor at its centre.
TEST(World, FloorUnderRoofMissesTheRoofsFormFactor) {
    const test::SceneArrays s = test::opposed_unit_squares(1.0f, Rgb(0.5), Rgb(0.0));
    BakeSettings settings;
    settings.world = WorldLight::uniform(Rgb(1.0), 4096);
    const BakeResult r = bake(s.input(), settings);
    const Elements& e = r.build.elements;
    ASSERT_EQ(e.size(), 2u);
    EXPECT_NEAR(r.solve.radiance[1].g, 0.5 * (1.0 - kParallelArea), 0.002 * 0.5 * (1.0 - kParallelArea));
    EXPECT_DOUBLE_EQ(r.solve.radiance[0].g, 0.0);  // the roof is black

    const std::vector<Rgb> E = world_irradiance_at(e, settings.world, {Vec3(0.5f, 0.5f, 0.0f)}, {Vec3(0, 0, 1)});
    EXPECT_NEAR(E[0].g, M_PI * (1.0 - kParallelCentre), 0.002 * M_PI * (1.0 - kParallelCentre));
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
/// by drawing from the map; the truth is the map's exact integral, pixel by pixel.
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
