/// @file test_sizes_by_sight.cpp
/// @brief Elements sized by the distance their polygon sees other surfaces at: a trench under a
/// bridge, its covered end against a dense direct solve over 10 cm elements; and what the uniform
/// bake and its clusters make of those sizes.
#include "bake/bake.h"
#include "geometry/clusters.h"
#include "testing/dense_solve.h"
#include "testing/test_util.h"
#include "transport/form_factors.h"
#include "visibility/sizes_by_sight.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace radiosity {
namespace {

constexpr float kElementSize = 4.0f;  // a game level's at Medium: far longer than the trench is wide
const Rgb kGrey(0.7);

/// A trench 0.4 m wide, 0.8 m deep and 6 m long (x in [0, 0.4], y in [0, 6], z in [-0.8, 0]), its
/// first 1.5 m covered by a bridge (its underside at z = 0), lit by a 1 m square emitter 2 m above
/// the open part; the ground beside it a 20 m plane of its own on each side.
/// Polygons: 0, 1 the walls, 2 the floor, 3, 4 the ends, 5 the bridge, 6 the emitter, 7, 8 the ground.
test::SceneArrays trench(bool ground) {
    test::SceneArrays scene;
    scene.add_quad({0, 0, -0.8f}, {0, 6, -0.8f}, {0, 6, 0}, {0, 0, 0}, kGrey);                // wall, +x
    scene.add_quad({0.4f, 0, -0.8f}, {0.4f, 0, 0}, {0.4f, 6, 0}, {0.4f, 6, -0.8f}, kGrey);    // wall, -x
    scene.add_quad({0, 0, -0.8f}, {0.4f, 0, -0.8f}, {0.4f, 6, -0.8f}, {0, 6, -0.8f}, kGrey);  // floor
    scene.add_quad({0, 0, -0.8f}, {0, 0, 0}, {0.4f, 0, 0}, {0.4f, 0, -0.8f}, kGrey);          // end, +y
    scene.add_quad({0, 6, -0.8f}, {0.4f, 6, -0.8f}, {0.4f, 6, 0}, {0, 6, 0}, kGrey);          // end, -y
    scene.add_quad({0, 0, 0}, {0, 1.5f, 0}, {0.4f, 1.5f, 0}, {0.4f, 0, 0}, kGrey);            // bridge, -z
    scene.add_quad({-0.3f, 2, 2}, {-0.3f, 3, 2}, {0.7f, 3, 2}, {0.7f, 2, 2}, Rgb(0.0), Rgb(10.0));
    if (ground) {
        scene.add_quad({-20, -7, 0}, {0, -7, 0}, {0, 13, 0}, {-20, 13, 0}, kGrey);
        scene.add_quad({0.4f, -7, 0}, {20.4f, -7, 0}, {20.4f, 13, 0}, {0.4f, 13, 0}, kGrey);
    }
    return scene;
}

/// The mean radiance (green) over the part of `polygon` with y below `y`: each element weighted by
/// its area times the share of its extent along y below `y`.
double covered_mean(const Elements& elements, const std::vector<Rgb>& radiance, int32_t polygon, float y) {
    double sum = 0.0, area = 0.0;
    for (std::size_t e = 0; e < elements.size(); ++e) {
        if (elements.polygon[e] != polygon || elements.is_back(e)) continue;
        float lo = INFINITY, hi = -INFINITY;
        for (int k = 0; k < elements.corner_count(e); ++k) {
            lo = std::min(lo, elements.vertices[std::size_t(elements.corners[e][k])].y);
            hi = std::max(hi, elements.vertices[std::size_t(elements.corners[e][k])].y);
        }
        const double share = hi > lo ? std::clamp(double(y - lo) / double(hi - lo), 0.0, 1.0) : double(lo < y);
        sum += share * double(elements.area[e]) * radiance[e].g;
        area += share * double(elements.area[e]);
    }
    return sum / area;
}

/// The elements of `input` built with `limits`, solved densely (hemi-cubes of resolution 128).
std::vector<Rgb> dense_light(const Elements& elements) {
    return test::direct_solve(elements, test::dense(compute_form_factors(elements, 128)));
}

TEST(SizesBySight, ATrenchIsCutToTheDistanceItsSidesSeeEachOtherAt) {
    const test::SceneArrays scene = trench(true);
    const Elements elements = build_elements(scene.input(), kElementSize).elements;
    const std::vector<float> sizes = sizes_by_sight(elements, scene.input().face_count, kElementSize);
    ASSERT_EQ(sizes.size(), 9u);
    for (int32_t p : {0, 1, 2, 5}) {
        std::printf("polygon %d: size %.3f m\n", p, sizes[std::size_t(p)]);
        EXPECT_GE(sizes[std::size_t(p)], kElementSize / 8.0f) << p;  // the floor under them
        EXPECT_LE(sizes[std::size_t(p)], kElementSize / 4.0f) << p;
    }
    // The open ground and the emitter keep the element size; the ends are single elements already.
    for (int32_t p : {6, 7, 8}) EXPECT_EQ(sizes[std::size_t(p)], 0.0f) << p;
    EXPECT_TRUE(any_size(sizes));
}

TEST(SizesBySight, TheCoveredEndOfATrenchAgreesWithTheDenseSolve) {
    // Truth: the dense direct solve over 10 cm elements (the trench's width in 4). Elements of the
    // element size spread the lit part's light over the covered end; elements sized by sight do not.
    const test::SceneArrays scene = trench(false);
    const SceneInput input = scene.input();
    const Elements fine = build_elements(input, 0.1f).elements;
    const std::vector<Rgb> truth = dense_light(fine);
    const Elements coarse = build_elements(input, kElementSize).elements;
    ElementLimits limits;
    limits.polygon_edge = sizes_by_sight(coarse, input.face_count, kElementSize);
    const Elements sized = build_elements(input, kElementSize, limits).elements;
    const std::vector<Rgb> coarse_light = dense_light(coarse), sized_light = dense_light(sized);
    for (const auto& [polygon, name] :
         {std::pair<int32_t, const char*>{2, "floor"}, {5, "bridge's underside"}, {0, "wall"}}) {
        const double exact = covered_mean(fine, truth, polygon, 1.5f);
        const double by_size = covered_mean(coarse, coarse_light, polygon, 1.5f);
        const double by_sight = covered_mean(sized, sized_light, polygon, 1.5f);
        std::printf(
            "covered %s: dense %.5f; %zu elements of the element size %.5f (%+.1f%%); %zu sized by sight "
            "%.5f (%+.1f%%)\n",
            name, exact, coarse.size(), by_size, 100.0 * (by_size / exact - 1.0), sized.size(), by_sight,
            100.0 * (by_sight / exact - 1.0));
        EXPECT_NEAR(by_sight / exact, 1.0, 0.15) << name;
        if (polygon == 5) EXPECT_GT(by_size / exact, 2.0) << name;  // what the element size alone gives
    }
}

TEST(SizesBySight, ClustersMergeNoFurtherThanTheirPolygonsSize) {
    // A 2 m square of 16 x 16 faces: merged up to the element size (1 m) it is 2 x 2 elements;
    // with its faces' polygons sized to 0.25 m, 8 x 8.
    test::SceneArrays square;
    square.add_grid(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0), 16, kGrey);
    const SceneInput input = square.input();
    const Elements faces = build_elements(input, 1.0f).elements;
    EXPECT_EQ(cluster_elements(faces, input, 1.0f).elements.size(), 4u);
    const std::vector<float> sized(input.face_count, 0.25f);
    EXPECT_EQ(cluster_elements(faces, input, 1.0f, {}, sized).elements.size(), 64u);
}

TEST(SizesBySight, TheUniformBakeSolvesTheTrenchAtItsSizes) {
    const test::SceneArrays scene = trench(true);
    BakeSettings settings;
    settings.element_size = kElementSize;
    settings.resolution = 64;
    const BakePlan planned = plan(scene.input(), settings);
    const Elements coarse = build_elements(scene.input(), kElementSize, settings.limits).elements;
    EXPECT_GT(planned.build.elements.size(), coarse.size());
    EXPECT_FALSE(planned.build.polygon_edge.empty());
    const BakeResult baked = bake(scene.input(), settings);
    EXPECT_EQ(baked.build.elements.size(), planned.build.elements.size());
    EXPECT_EQ(baked.solve_elements, planned.solve_elements);
}

}  // namespace
}  // namespace radiosity
