/// @file test_layers.cpp
/// @brief Light group layers (layers.h): the layers sum to the total, the total is the ordinary
/// bake (light is linear in its sources), and each layer is the bake of its own sources alone.
#include "bake/layers.h"

#include "testing/test_util.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace radiosity {
namespace {

const Rgb kWhite(0.73), kRed(0.65, 0.05, 0.05), kBlack(0.0);

/// A floor with a red wall and a block, open to the sky, under an emitting panel (polygon 2 of
/// its emission `panel`).
test::SceneArrays lit_floor(const Rgb& panel) {
    test::SceneArrays s;
    s.add_quad({0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, kWhite);           // floor
    s.add_quad({0, 0, 0}, {0, 2, 0}, {0, 2, 1}, {0, 0, 1}, kRed, kBlack, 1);  // wall facing +x
    s.add_quad({0.8f, 0.8f, 1.5f}, {0.8f, 1.2f, 1.5f}, {1.2f, 1.2f, 1.5f}, {1.2f, 0.8f, 1.5f}, kBlack, panel, 2);
    const float a = 0.9f, b = 1.3f, h = 0.4f;  // a block on the floor: four sides and a top
    s.add_quad({a, a, h}, {b, a, h}, {b, b, h}, {a, b, h}, kWhite);
    s.add_quad({a, a, 0}, {b, a, 0}, {b, a, h}, {a, a, h}, kWhite);
    s.add_quad({b, a, 0}, {b, b, 0}, {b, b, h}, {b, a, h}, kWhite);
    s.add_quad({b, b, 0}, {a, b, 0}, {a, b, h}, {b, b, h}, kWhite);
    s.add_quad({a, b, 0}, {a, a, 0}, {a, a, h}, {a, b, h}, kWhite);
    return s;
}

/// A point lamp, soft (radius 0.1 m) or sharp (a point).
PointLight point_lamp(bool soft = true) {
    PointLight lamp;
    lamp.position = Vec3(1.5f, 0.6f, 1.0f);
    lamp.intensity = Rgb(2.0, 1.5, 1.0);
    lamp.radius = soft ? 0.1f : 0.0f;
    return lamp;
}

/// A sun, soft (0.1 radians across) or sharp.
SunLight sun(bool soft = true) {
    SunLight s;
    s.direction = glm::normalize(Vec3(0.3f, 0.2f, -1.0f));
    s.irradiance = Rgb(1.0, 0.9, 0.8);
    s.half_angle = soft ? 0.05f : 0.0f;
    return s;
}

/// Gauss-Seidel to 1e-10 with the final gather (and its field) on, the lamp and the sun, the sky.
BakeSettings all_sources(bool soft = true) {
    BakeSettings s;
    s.element_size = 0.25f;
    s.resolution = 64;
    s.solve.tolerance = 1e-10;
    s.final_gather.enabled = true;
    s.final_gather.rays = 64;
    s.final_gather.shadow_rays = 16;
    s.final_gather.field_rays = 16;
    s.lights.points = {point_lamp(soft)};
    s.lights.suns = {sun(soft)};
    s.world = WorldLight::uniform(Rgb(0.2, 0.25, 0.3));
    return s;
}

/// The panel (polygon 2) in layer 0, the lamp in 1, the sun and the sky in 2.
LayerSources three_groups(std::size_t polygons) {
    LayerSources sources;
    sources.count = 3;
    sources.polygon.assign(polygons, 0);
    sources.point = {1};
    sources.sun = {2};
    sources.world = 2;
    return sources;
}

/// The largest difference between two sets of corner colours, as a share of the largest colour in `b`.
double worst_difference(const std::vector<Rgb>& a, const std::vector<Rgb>& b) {
    EXPECT_EQ(a.size(), b.size());
    double worst = 0.0, peak = 0.0;
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
        peak = std::max(peak, max_channel(b[i]));
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(a[i][c] - b[i][c]));
    }
    return peak > 0.0 ? worst / peak : worst;
}

TEST(Layers, SumToTheTotalAndTheTotalIsTheOrdinaryBakeWhereNothingIsClamped) {
    const test::SceneArrays scene = lit_floor(Rgb(8.0));
    const BakeSettings settings = all_sources(false);
    const LayeredBake layered = bake_layers(scene.input(), settings, three_groups(scene.material.size()));
    ASSERT_EQ(layered.layers.size(), 3u);
    std::vector<Rgb> sum(layered.total.colors.input_corner.size(), Rgb(0.0));
    for (const BakeResult& layer : layered.layers) {
        ASSERT_TRUE(layer.solve.converged);
        double peak = 0.0;
        for (std::size_t i = 0; i < sum.size(); ++i) {
            sum[i] += layer.colors.input_corner[i];
            peak = std::max(peak, max_channel(layer.colors.input_corner[i]));
        }
        EXPECT_GT(peak, 0.0);  // every group lights the scene
    }
    EXPECT_LT(worst_difference(sum, layered.total.colors.input_corner), 1e-12);
    // The total's cost is every layer's gather: their rays add, the points gathered are the geometry's.
    std::uint64_t rays = 0;
    for (const BakeResult& layer : layered.layers) rays += layer.gather_cost.rays();
    EXPECT_GT(rays, 0u);
    EXPECT_EQ(layered.total.gather_cost.rays(), rays);
    EXPECT_EQ(layered.total.gather_cost.gathered, layered.layers[0].gather_cost.gathered);
    EXPECT_EQ(layered.total.interpolated_points, layered.layers[0].interpolated_points);
    // One bake with every source: the transport is linear, so the same light on every element.
    const BakeResult ordinary = bake(scene.input(), settings);
    EXPECT_LT(worst_difference(layered.total.solve.radiance, ordinary.solve.radiance), 1e-6);
    EXPECT_LT(worst_difference(layered.total.build.elements.emission, ordinary.build.elements.emission), 1e-9);
    // At the corners, light below zero is clamped (interpolation extrapolates across a sharp
    // shadow's edge; the gather's reads of it): in each layer, where the ordinary bake clamps only
    // the sum. Clamping takes out negative light only, so the layers' sum is never the darker, and
    // elsewhere it is the ordinary bake's colour (sharp lamps: a soft lamp's shadow rays are seeded
    // by its place among the lamps lighting with it, so there the total is as exact, not the same noise).
    const std::vector<Rgb>& total = layered.total.colors.input_corner;
    const std::vector<Rgb>& plain = ordinary.colors.input_corner;
    double peak = 0.0;
    for (const Rgb& c : plain) peak = std::max(peak, max_channel(c));
    std::size_t same = 0;
    for (std::size_t i = 0; i < total.size(); ++i) {
        for (int c = 0; c < 3; ++c) EXPECT_GE(total[i][c], plain[i][c] - 1e-6 * peak) << i;
        same += max_channel(glm::abs(total[i] - plain[i])) <= 1e-6 * peak;
    }
    EXPECT_GT(same, total.size() * 3 / 4);
}

TEST(Layers, EachLayerIsTheBakeOfItsSourcesAlone) {
    const test::SceneArrays scene = lit_floor(Rgb(8.0));
    const BakeSettings settings = all_sources();
    const LayeredBake layered = bake_layers(scene.input(), settings, three_groups(scene.material.size()));

    BakeSettings panel_only = settings;
    panel_only.lights = Lights();
    panel_only.world = WorldLight();
    EXPECT_EQ(layered.layers[0].colors.input_corner, bake(scene.input(), panel_only).colors.input_corner);

    // Without the panel's light its polygon is one-sided and black: the same light, other elements.
    const test::SceneArrays dark = lit_floor(Rgb(0.0));
    BakeSettings lamp_only = panel_only;
    lamp_only.lights.points = {point_lamp()};
    EXPECT_LT(
        worst_difference(layered.layers[1].colors.input_corner, bake(dark.input(), lamp_only).colors.input_corner),
        1e-9);
    BakeSettings sky_only = panel_only;
    sky_only.lights.suns = {sun()};
    sky_only.world = settings.world;
    EXPECT_LT(worst_difference(layered.layers[2].colors.input_corner, bake(dark.input(), sky_only).colors.input_corner),
              1e-9);
}

TEST(Layers, LampsAndSkyLayersAreBitForBitTheirBakesAlone) {
    // No emitting polygon: leaving a group's sources out changes no element.
    const test::SceneArrays scene = lit_floor(Rgb(0.0));
    BakeSettings settings = all_sources();
    PointLight second = point_lamp();
    second.position = Vec3(0.5f, 1.5f, 0.8f);
    second.intensity = Rgb(1.0, 1.0, 3.0);
    settings.lights.points.push_back(second);
    LayerSources sources = three_groups(scene.material.size());
    sources.point = {0, 1};  // two lamps, two groups; the sun and the sky in the third
    const LayeredBake layered = bake_layers(scene.input(), settings, sources);
    for (int32_t k = 0; k < 3; ++k) {
        BakeSettings alone = settings;
        alone.lights.points.clear();
        alone.lights.suns.clear();
        if (k < 2) alone.lights.points = {settings.lights.points[std::size_t(k)]};
        if (k == 2) alone.lights.suns = settings.lights.suns;
        if (k != 2) alone.world = WorldLight();
        const BakeResult single = bake(scene.input(), alone);
        EXPECT_EQ(layered.layers[std::size_t(k)].colors.input_corner, single.colors.input_corner) << "layer " << k;
        EXPECT_EQ(layered.layers[std::size_t(k)].light_colors.input_corner, single.light_colors.input_corner);
    }
}

TEST(Layers, OverOneRefinedHierarchy) {
    // The links and leaves are refined once, for all sources: the layers' total is the hierarchical
    // bake's light on the same leaves, to the solve's tolerance.
    const test::SceneArrays scene = lit_floor(Rgb(8.0));
    BakeSettings settings = all_sources(false);
    settings.hierarchical.enabled = true;
    settings.hierarchical.refine_tolerance = 0.05;
    const LayeredBake layered = bake_layers(scene.input(), settings, three_groups(scene.material.size()));
    const BakeResult ordinary = bake(scene.input(), settings);
    ASSERT_EQ(layered.total.build.elements.size(), ordinary.build.elements.size());
    EXPECT_EQ(layered.total.build.elements.vertices, ordinary.build.elements.vertices);
    std::vector<Rgb> sum(layered.total.colors.input_corner.size(), Rgb(0.0));
    for (const BakeResult& layer : layered.layers) {
        ASSERT_TRUE(layer.solve.converged);
        for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += layer.colors.input_corner[i];
    }
    EXPECT_LT(worst_difference(sum, layered.total.colors.input_corner), 1e-12);
    EXPECT_LT(worst_difference(layered.total.solve.radiance, ordinary.solve.radiance), 1e-6);
    EXPECT_LT(worst_difference(layered.total.build.elements.emission, ordinary.build.elements.emission), 1e-6);
    ASSERT_TRUE(layered.total.hierarchy.has_value());
    EXPECT_EQ(layered.total.hierarchy->leaves, ordinary.hierarchy->leaves);
}

TEST(Layers, RefusesMediaTheUngatheredHierarchyAndLayersOutOfRange) {
    const test::SceneArrays scene = lit_floor(Rgb(8.0));
    BakeSettings settings = all_sources();
    LayerSources sources = three_groups(scene.material.size());
    sources.world = 3;
    EXPECT_THROW(bake_layers(scene.input(), settings, sources), InputError);
    sources.world = 2;
    sources.point.clear();
    EXPECT_THROW(bake_layers(scene.input(), settings, sources), InputError);
    settings.hierarchical.enabled = true;
    settings.final_gather.enabled = false;
    EXPECT_THROW(bake_layers(scene.input(), settings, three_groups(scene.material.size())), InputError);
}

TEST(Layers, MemoryBound) {
    // Per layer: 2 colours per input corner, 2 x 4 per element's corners, 2 per element, 24 bytes each.
    EXPECT_EQ(layer_bytes_bound(8, 1000, 4000), 8u * (8000u + 8000u + 2000u) * 24u);
}

}  // namespace
}  // namespace radiosity
