/// @file test_stability_input.cpp
/// @brief Degenerate input through bake(): zero-area and non-finite polygons, tiny and enormous
/// scales, absurd element counts. A clear error or a skipped polygon, never a hang or NaN colours.

#include "bake/bake.h"
#include "testing/test_util.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>

using namespace radiosity;

namespace {

BakeSettings settings(float element_size) {
    BakeSettings s;
    s.element_size = element_size;
    s.resolution = 32;
    s.solve.tolerance = 1e-7;
    return s;
}

void expect_finite(const BakeResult& r) {
    for (const Rgb& L : r.solve.radiance) ASSERT_TRUE(std::isfinite(L.r) && std::isfinite(L.g) && std::isfinite(L.b));
    for (const Rgb& L : r.colors.input_corner)
        ASSERT_TRUE(std::isfinite(L.r) && std::isfinite(L.g) && std::isfinite(L.b));
}

}  // namespace

TEST(DegenerateInput, FurnaceHoldsFromMicrometresToThousandsOfKilometres) {
    // Form factors are scale-free; so must be every tolerance inside (zero area, edge-on, near plane).
    for (float size : {1e-6f, 1e-3f, 1.0f, 1e3f, 1e6f}) {
        const test::SceneArrays box = test::closed_box(Vec3(size, 1.5f * size, 0.8f * size), Rgb(0.5), Rgb(1.0));
        const BakeResult r = bake(box.input(), settings(0.3f * size));
        ASSERT_TRUE(r.build.skipped.empty()) << size;
        ASSERT_EQ(test::front_count(r.build.elements), 94u) << size;
        ASSERT_EQ(r.build.elements.size(), 2 * 94u) << size;  // the emitting walls' back sides, facing out
        expect_finite(r);
        double worst = 0.0;
        for (const Rgb& L : test::fronts(r.build.elements, r.solve.radiance))
            worst = std::max(worst, std::abs(L.g / 2.0 - 1.0));
        std::printf("furnace box of %g m: worst deviation %.1e\n", double(size), worst);
        EXPECT_LT(worst, 1e-4) << size;
    }
}

TEST(DegenerateInput, BadPolygonsAreSkippedAndNamedTheRestBakes) {
    test::SceneArrays scene = test::closed_box(Vec3(1.0f), Rgb(0.5), Rgb(1.0));
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    scene.add_quad({0.2f, 0.2f, 0.5f}, {0.4f, 0.2f, 0.5f}, {0.4f, 0.2f, 0.5f}, {0.2f, 0.2f, 0.5f},
                   Rgb(0.5));  // zero area
    scene.add_polygon({{0.2f, 0.2f, 0.5f}, {nan, 0.2f, 0.5f}, {0.2f, 0.4f, 0.5f}}, Rgb(0.5), Rgb(0));
    scene.add_polygon({{0.2f, 0.2f, 0.5f}, {inf, 0.2f, 0.5f}, {0.2f, 0.4f, 0.5f}}, Rgb(0.5), Rgb(0));
    scene.add_polygon({{0.2f, 0.2f, 0.5f}, {0.3f, 0.2f, 0.5f}, {0.4f, 0.2f, 0.5f}}, Rgb(0.5), Rgb(0));  // collinear
    const BakeResult r = bake(scene.input(), settings(0.25f));
    ASSERT_EQ(r.build.skipped.size(), 4u);
    EXPECT_EQ(r.build.skipped[0].defect, Defect::ZeroArea);
    EXPECT_EQ(r.build.skipped[1].defect, Defect::NonFinite);
    EXPECT_EQ(r.build.skipped[2].defect, Defect::NonFinite);
    EXPECT_EQ(r.build.skipped[3].defect, Defect::ZeroArea);
    expect_finite(r);
    for (const Rgb& L : test::fronts(r.build.elements, r.solve.radiance)) EXPECT_NEAR(L.g, 2.0, 2e-4);
}

TEST(DegenerateInput, NonFiniteMaterialIsAnInputErrorNamingThePolygon) {
    for (int which : {0, 1}) {
        test::SceneArrays scene = test::closed_box(Vec3(1.0f), Rgb(0.5), Rgb(1.0));
        (which ? scene.emission : scene.reflectance)[3 * 4 + 1] = std::numeric_limits<float>::quiet_NaN();
        try {
            bake(scene.input(), settings(0.5f));
            ADD_FAILURE() << "no error";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("polygon 4"), std::string::npos) << e.what();
        }
    }
}

TEST(DegenerateInput, TooManyElementsIsAClearErrorNotAHang) {
    // A 1e6 m floor at 1 cm elements would be 1e16 elements; 1e6 m at 1e-6 m overflows an int.
    for (float element_size : {0.01f, 1e-6f}) {
        test::SceneArrays scene;
        scene.add_quad({0, 0, 0}, {1e6f, 0, 0}, {1e6f, 1e6f, 0}, {0, 1e6f, 0}, Rgb(0.5), Rgb(1.0));
        const auto start = std::chrono::steady_clock::now();
        try {
            bake(scene.input(), settings(element_size));
            ADD_FAILURE() << "no error";
        } catch (const InputError& e) {
            std::printf("%s\n", e.what());
            EXPECT_NE(std::string(e.what()).find("polygon 0"), std::string::npos);
            EXPECT_NE(std::string(e.what()).find("cap"), std::string::npos);
        }
        EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
    }
    // The cap counts the whole scene: many polygons just under it each still add up.
    BakeSettings s = settings(0.1f);
    s.limits.max_elements = 150;
    EXPECT_THROW(bake(test::closed_box(Vec3(1.0f), Rgb(0.5), Rgb(1.0)).input(), s), InputError);  // 6 x 100
    // The walls emit: each element has a back side, and the cap counts both.
    s.limits.max_elements = 1199;
    EXPECT_THROW(bake(test::closed_box(Vec3(1.0f), Rgb(0.5), Rgb(1.0)).input(), s), InputError);
    s.limits.max_elements = 1200;
    EXPECT_EQ(bake(test::closed_box(Vec3(1.0f), Rgb(0.5), Rgb(1.0)).input(), s).build.elements.size(), 1200u);
}
