/// @file test_bake_cache.cpp
/// @brief The cache between bakes of the same geometry (bake_cache.h): a re-bake after a lighting
/// or material edit reuses the elements, form factors and the gather's hits and gives, to the bit,
/// the colours of a bake from scratch; a change of geometry, or a cache over the memory budget,
/// bakes without it and says so.
#include "bake/bake_cache.h"
#include "bake/layers.h"

#include "testing/test_util.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <functional>
#include <string>

namespace radiosity {
namespace {

const Rgb kWhite(0.73), kRed(0.65, 0.05, 0.05), kBlack(0.0);

/// A floor with a red wall (polygon 1) and a block, open to the sky, under an emitting panel
/// (polygon 2).
test::SceneArrays lit_floor() {
    test::SceneArrays s;
    s.add_quad({0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, kWhite);
    s.add_quad({0, 0, 0}, {0, 2, 0}, {0, 2, 1}, {0, 0, 1}, kRed, kBlack, 1);
    s.add_quad({0.8f, 0.8f, 1.5f}, {0.8f, 1.2f, 1.5f}, {1.2f, 1.2f, 1.5f}, {1.2f, 0.8f, 1.5f}, kBlack, Rgb(8.0), 2);
    const float a = 0.9f, b = 1.3f, h = 0.4f;
    s.add_quad({a, a, h}, {b, a, h}, {b, b, h}, {a, b, h}, kWhite);
    s.add_quad({a, a, 0}, {b, a, 0}, {b, a, h}, {a, a, h}, kWhite);
    s.add_quad({b, a, 0}, {b, b, 0}, {b, b, h}, {b, a, h}, kWhite);
    s.add_quad({b, b, 0}, {a, b, 0}, {a, b, h}, {b, b, h}, kWhite);
    s.add_quad({a, b, 0}, {a, a, 0}, {a, a, h}, {a, b, h}, kWhite);
    return s;
}

/// Two soft point lamps, a soft sun and the sky; Gauss-Seidel with the final gather, its field and
/// its sharing between corners.
BakeSettings lit_settings() {
    BakeSettings s;
    s.element_size = 0.25f;
    s.resolution = 64;
    s.solve.tolerance = 1e-8;
    s.final_gather.enabled = true;
    s.final_gather.rays = 64;
    s.final_gather.shadow_rays = 16;
    s.final_gather.field_rays = 16;
    s.final_gather.cache_accuracy = 0.15;
    PointLight lamp;
    lamp.position = Vec3(1.5f, 0.6f, 1.0f);
    lamp.intensity = Rgb(2.0, 1.5, 1.0);
    lamp.radius = 0.1f;
    PointLight second = lamp;
    second.position = Vec3(0.5f, 1.5f, 0.8f);
    second.intensity = Rgb(1.0, 1.0, 3.0);
    s.lights.points = {lamp, second};
    SunLight sun;
    sun.direction = glm::normalize(Vec3(0.3f, 0.2f, -1.0f));
    sun.irradiance = Rgb(1.0, 0.9, 0.8);
    sun.half_angle = 0.05f;
    s.lights.suns = {sun};
    s.world = WorldLight::uniform(Rgb(0.2, 0.25, 0.3));
    return s;
}

void expect_same_bake(const BakeResult& a, const BakeResult& b, const std::string& what) {
    EXPECT_EQ(a.colors.input_corner, b.colors.input_corner) << what;
    EXPECT_EQ(a.light_colors.input_corner, b.light_colors.input_corner) << what;
    EXPECT_EQ(a.colors.element_corner, b.colors.element_corner) << what;
    EXPECT_EQ(a.solve.radiance, b.solve.radiance) << what;
    EXPECT_EQ(a.build.elements.emission, b.build.elements.emission) << what;
}

/// An edit of the lighting or of a material: the scene's arrays and the settings.
struct Edit {
    std::string name;
    std::function<void(test::SceneArrays&, BakeSettings&)> apply;
};

std::vector<Edit> lighting_edits() {
    return {
        {"a lamp's power", [](test::SceneArrays&, BakeSettings& s) { s.lights.points[0].intensity *= 3.0; }},
        {"a lamp's colour", [](test::SceneArrays&, BakeSettings& s) { s.lights.points[1].intensity = Rgb(3, 1, 0.2); }},
        {"a lamp's position", [](test::SceneArrays&, BakeSettings& s) { s.lights.points[0].position.x -= 0.4f; }},
        {"a lamp's size", [](test::SceneArrays&, BakeSettings& s) { s.lights.points[1].radius = 0.3f; }},
        {"the sun", [](test::SceneArrays&, BakeSettings& s) { s.lights.suns[0].direction = Vec3(0, 0, -1); }},
        {"the sky", [](test::SceneArrays&, BakeSettings& s) { s.world = WorldLight::uniform(Rgb(0.5, 0.4, 0.1)); }},
        {"an emission's strength", [](test::SceneArrays& a, BakeSettings&) { a.emission[6] = a.emission[7] = 2.0f; }},
        {"a material's colour",
         [](test::SceneArrays& a, BakeSettings&) {
             a.reflectance[3] = 0.05f;
             a.reflectance[5] = 0.7f;
         }},
    };
}

TEST(BakeCache, TheFirstBakeIsTheBakeWithoutACache) {
    const test::SceneArrays scene = lit_floor();
    BakeCache cache;
    const BakeResult cached = bake(scene.input(), lit_settings(), {}, &cache);
    ASSERT_TRUE(cached.cache.has_value());
    EXPECT_FALSE(cached.cache->reused);
    EXPECT_EQ(cached.cache->not_reused, "no earlier bake was kept");
    EXPECT_TRUE(cached.cache->kept);
    EXPECT_EQ(cached.cache->bytes, cache.bytes());
    EXPECT_GT(cache.bytes(), 0u);
    expect_same_bake(cached, bake(scene.input(), lit_settings()), "first bake");
}

TEST(BakeCache, AReBakeAfterALightingOrMaterialEditIsTheBakeFromScratch) {
    test::SceneArrays scene = lit_floor();
    BakeSettings settings = lit_settings();
    BakeCache cache;
    bake(scene.input(), settings, {}, &cache);
    for (const Edit& edit : lighting_edits()) {
        edit.apply(scene, settings);
        const BakeResult again = bake(scene.input(), settings, {}, &cache);
        ASSERT_TRUE(again.cache.has_value());
        EXPECT_TRUE(again.cache->reused) << edit.name << ": " << again.cache->not_reused;
        EXPECT_TRUE(again.cache->kept) << edit.name;
        EXPECT_EQ(again.seconds_form_factors, 0.0);
        const BakeResult fresh = bake(scene.input(), settings);
        expect_same_bake(again, fresh, edit.name);
        // The gather read its indirect and probe rays' hits: it traced the shadow rays alone.
        EXPECT_EQ(again.gather_cost.probes.rays, 0u) << edit.name;
        EXPECT_GT(fresh.gather_cost.probes.rays, 0u) << edit.name;
        EXPECT_LT(again.gather_cost.rays(), fresh.gather_cost.rays()) << edit.name;
    }
}

TEST(BakeCache, AReBakeAfterALampMovedBesideMergedFacesMergesThemAgain) {
    // A floor of 16 x 16 faces, half the element size each: the solve merges them, and beside a
    // point lamp its clusters follow the lamp's distance (cluster_elements). A lamp moved 1 m over
    // the floor leaves the clusters as they were, and the re-bake reuses everything; a lamp brought
    // 0.3 m over it changes them, and the re-bake merges the faces again and computes their form
    // factors anew, reading the gather's recorded hits as before. Either way the colours are the
    // bake from scratch's.
    test::SceneArrays scene;
    scene.add_grid(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0), 16, kWhite);
    scene.add_quad({0, 0, 0}, {0, 2, 0}, {0, 2, 1}, {0, 0, 1}, kRed, kBlack, 1);
    BakeSettings settings = lit_settings();
    BakeCache cache;
    const BakeResult first = bake(scene.input(), settings, {}, &cache);
    ASSERT_LT(first.solve_elements, first.build.elements.size());
    settings.lights.points[0].position.x -= 0.4f;
    const BakeResult aside = bake(scene.input(), settings, {}, &cache);
    EXPECT_TRUE(aside.cache->reused) << aside.cache->not_reused;
    EXPECT_FALSE(aside.cache->merged_again);
    EXPECT_EQ(aside.seconds_form_factors, 0.0);
    expect_same_bake(aside, bake(scene.input(), settings), "a lamp 1 m over the floor moved");
    settings.lights.points[0].position = Vec3(1.0f, 1.0f, 0.3f);
    const BakeResult near = bake(scene.input(), settings, {}, &cache);
    EXPECT_TRUE(near.cache->reused) << near.cache->not_reused;
    EXPECT_TRUE(near.cache->merged_again);
    EXPECT_GT(near.seconds_form_factors, 0.0);
    EXPECT_GT(near.solve_elements, first.solve_elements);
    const BakeResult fresh = bake(scene.input(), settings);
    expect_same_bake(near, fresh, "a lamp brought 0.3 m over the floor");
    EXPECT_EQ(near.gather_cost.probes.rays, 0u);  // the gather read its recorded hits
    EXPECT_LT(near.gather_cost.rays(), fresh.gather_cost.rays());
}

TEST(BakeCache, AReBakeTracesShadowRaysTowardsTheChangedSourcesAlone) {
    test::SceneArrays scene = lit_floor();
    BakeSettings settings = lit_settings();
    BakeCache cache;
    const BakeResult first = bake(scene.input(), settings, {}, &cache);
    ASSERT_TRUE(first.cache->kept);
    EXPECT_GT(first.cache->direct_bytes, 0u);
    EXPECT_LT(first.cache->direct_bytes, first.cache->bytes);
    EXPECT_EQ(first.cache->bytes, cache.bytes());
    // Nothing changed: every hit and every source's light at every point is kept, no ray is traced.
    const BakeResult same = bake(scene.input(), settings, {}, &cache);
    EXPECT_EQ(same.gather_cost.rays(), 0u);
    expect_same_bake(same, first, "nothing changed");
    // An emission's strength changed alone: the emitter's visible share is kept, no ray is traced.
    for (int c = 0; c < 3; ++c) scene.emission[6 + c] *= 3.0f;
    const BakeResult brighter = bake(scene.input(), settings, {}, &cache);
    EXPECT_EQ(brighter.gather_cost.rays(), 0u);
    expect_same_bake(brighter, bake(scene.input(), settings), "an emission's strength");
    // One lamp moved: its shadow rays alone, fewer than a re-bake that moves every lamp and the sun.
    settings.lights.points[0].position.x -= 0.4f;
    const BakeResult one = bake(scene.input(), settings, {}, &cache);
    EXPECT_GT(one.gather_cost.rays(), 0u);
    for (PointLight& lamp : settings.lights.points) lamp.position.y += 0.1f;
    settings.lights.suns[0].direction = Vec3(0, 0, -1);
    const BakeResult all = bake(scene.input(), settings, {}, &cache);
    EXPECT_LT(3 * one.gather_cost.rays(), all.gather_cost.rays());
    expect_same_bake(all, bake(scene.input(), settings), "every lamp moved");
    // The moved lamps' old light is let go: what is kept stays one bake's.
    EXPECT_LE(all.cache->direct_bytes, first.cache->direct_bytes + first.cache->direct_bytes / 10);
}

TEST(BakeCache, AChangeOfGeometryOrOfWhatEmitsBakesAfresh) {
    test::SceneArrays scene = lit_floor();
    const BakeSettings settings = lit_settings();
    BakeCache cache;
    bake(scene.input(), settings, {}, &cache);
    scene.positions[3 * 9 + 2] += 0.05f;  // the block's top corner rises
    const BakeResult moved = bake(scene.input(), settings, {}, &cache);
    EXPECT_FALSE(moved.cache->reused);
    EXPECT_EQ(moved.cache->not_reused, "the geometry, or a setting that chooses the elements, changed");
    EXPECT_TRUE(moved.cache->kept);
    expect_same_bake(moved, bake(scene.input(), settings), "moved vertex");

    scene.emission[0] = 0.5f;  // the floor emits: its elements get back sides
    EXPECT_FALSE(bake(scene.input(), settings, {}, &cache).cache->reused);
    BakeSettings finer = settings;
    finer.element_size = 0.2f;
    EXPECT_FALSE(bake(scene.input(), finer, {}, &cache).cache->reused);
    EXPECT_TRUE(bake(scene.input(), finer, {}, &cache).cache->reused);
    BakeSettings unmerged = finer;  // one unknown per face's element: other solve elements
    unmerged.merge_elements = false;
    const BakeResult own = bake(scene.input(), unmerged, {}, &cache);
    EXPECT_FALSE(own.cache->reused);
    expect_same_bake(own, bake(scene.input(), unmerged), "elements not merged");
}

TEST(BakeCache, OverTheMemoryBudgetItBakesWithoutKeepingIt) {
    const test::SceneArrays scene = lit_floor();
    BakeSettings settings = lit_settings();
    settings.matrix_budget_bytes = 64 << 10;  // F on demand; no room for the gather's hits
    BakeCache cache;
    const BakeResult result = bake(scene.input(), settings, {}, &cache);
    EXPECT_FALSE(result.cache->kept);
    EXPECT_EQ(result.cache->not_kept,
              "the elements, form factors and the final gather's rays need more than the memory budget (0 MB)");
    EXPECT_TRUE(cache.empty());
    EXPECT_EQ(cache.bytes(), 0u);
    expect_same_bake(result, bake(scene.input(), settings), "over the budget");
}

TEST(BakeCache, TheHierarchicalMethodKeepsNone) {
    const test::SceneArrays scene = lit_floor();
    BakeSettings settings = lit_settings();
    BakeCache cache;
    bake(scene.input(), settings, {}, &cache);
    settings.hierarchical.enabled = true;
    const BakeResult result = bake(scene.input(), settings, {}, &cache);
    EXPECT_FALSE(result.cache->reused);
    EXPECT_FALSE(result.cache->kept);
    EXPECT_TRUE(cache.empty());
}

TEST(BakeCache, LayersReuseItAndEqualLayersBakedAfresh) {
    test::SceneArrays scene = lit_floor();
    BakeSettings settings = lit_settings();
    LayerSources sources;
    sources.count = 3;
    sources.polygon.assign(scene.material.size(), 0);
    sources.point = {1, 2};
    sources.sun = {2};
    sources.world = 0;
    BakeCache cache;
    const LayeredBake first = bake_layers(scene.input(), settings, sources, {}, &cache);
    EXPECT_FALSE(first.total.cache->reused);
    EXPECT_TRUE(first.total.cache->kept);
    settings.lights.points[0].position.y += 0.3f;
    const LayeredBake again = bake_layers(scene.input(), settings, sources, {}, &cache);
    EXPECT_TRUE(again.total.cache->reused);
    const LayeredBake fresh = bake_layers(scene.input(), settings, sources);
    ASSERT_EQ(again.layers.size(), fresh.layers.size());
    for (std::size_t k = 0; k < fresh.layers.size(); ++k)
        EXPECT_EQ(again.layers[k].colors.input_corner, fresh.layers[k].colors.input_corner) << "layer " << k;
    EXPECT_EQ(again.total.colors.input_corner, fresh.total.colors.input_corner);
    // A bake without layers over the same cache reads it too.
    EXPECT_TRUE(bake(scene.input(), settings, {}, &cache).cache->reused);
}

}  // namespace
}  // namespace radiosity
