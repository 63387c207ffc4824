/// @file test_messy_faces.cpp
/// @brief Zero-area, degenerate and sliver faces as bought models have them: the aspect cut makes
/// no more elements from a face than its size and area ask for, whatever its aspect, in the
/// uniform elements and in the hierarchy's patches; faces without area are skipped and reported.

#include "geometry/scene.h"
#include "testing/test_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

using namespace radiosity;
using test::SceneArrays;

namespace {

constexpr float kSize = 0.25f;  // element size

ElementLimits sliver_limits() {
    ElementLimits limits;
    limits.max_aspect = 4.0f;
    return limits;
}

/// A needle 1 m long in z = 0 whose short edge (at x = 1) is `width` wide.
std::vector<Vec3> needle(double width) { return {{0, 0, 0}, {1, 0, 0}, {1, float(width), 0}}; }

/// A cap: the longest edge 1 m along x, the apex `height` above the point x = 0.3.
std::vector<Vec3> cap(double height) { return {{0, 0, 0}, {1, 0, 0}, {0.3f, float(height), 0}}; }

std::size_t elements_of(const std::vector<Vec3>& polygon, float max_edge, const ElementLimits& limits) {
    SceneArrays s;
    s.add_polygon(polygon, Rgb(0.5), Rgb(0));
    const BuildResult r = build_elements(s.input(), max_edge, limits);
    EXPECT_TRUE(r.skipped.empty());
    const double area = std::accumulate(r.elements.area.begin(), r.elements.area.end(), 0.0);
    const double exact = 0.5 * std::abs(double(polygon[2].y)) * double(polygon[1].x - polygon[0].x);
    EXPECT_NEAR(area, exact, 1e-3 * exact);
    return r.elements.size();
}

}  // namespace

// Pieces are max(4 w, s/32, min(s, (s/32)^2 / w)) long along a strip w wide (s = 0.25 m): at
// w = 1 mm that is 6.1 cm (17 rows along 1 m); from w = s / 1024 (aspect 4096) on it is s itself,
// so the needle has the 4 rows its length asks for and the cap (strips of 0.3 m and 0.7 m) 2 + 3.
// (From aspect 1e7 on, 1 m slivers here are round-off: AHeightOfRoundOffIsNoArea.)
TEST(MessyFaces, ASliverOfAnyAspectMakesNoMoreElementsThanItsSizeAsks) {
    EXPECT_EQ(elements_of(needle(1e-3), kSize, sliver_limits()), 17u);
    for (const double aspect : {1e4, 1e5, 1e6}) {
        SCOPED_TRACE(aspect);
        EXPECT_EQ(elements_of(needle(1.0 / aspect), kSize, sliver_limits()), 4u);
        EXPECT_EQ(elements_of(cap(1.0 / aspect), kSize, sliver_limits()), 5u);
    }
}

// The hierarchy's patches (max_edge 0) take the bake's element size from the limits: the same rows.
TEST(MessyFaces, TheHierarchysPatchesAreBoundedByTheElementSizeToo) {
    ElementLimits limits = sliver_limits();
    limits.element_size = kSize;
    EXPECT_EQ(elements_of(needle(1e-3), 0.0f, limits), 17u);
    EXPECT_EQ(elements_of(needle(1e-6), 0.0f, limits), 4u);
    EXPECT_EQ(elements_of(cap(1e-6), 0.0f, limits), 5u);
    // With no element size the polygon's own 1 m is it, without the area floor: rows of 1/32 m at
    // most, and a 1 cm needle keeps its rows of 4 cm: 26 along its 1.00005 m (docs/stability.md).
    EXPECT_EQ(elements_of(needle(1e-6), 0.0f, sliver_limits()), 32u);
    EXPECT_EQ(elements_of(needle(1e-2), 0.0f, sliver_limits()), 26u);
}

// A 1 m x 1 um quad is cut as its length asks (4 pieces), not into a million.
TEST(MessyFaces, AThinQuadIsCutAsItsLengthAsks) {
    SceneArrays s;
    s.add_quad({0, 0, 0}, {1, 0, 0}, {1, 1e-6f, 0}, {0, 1e-6f, 0}, Rgb(0.5));
    EXPECT_EQ(build_elements(s.input(), kSize, sliver_limits()).elements.size(), 4u);
}

// A book triangle from a downloaded model: three nearly collinear points 26 cm apart, area
// 3.6e-9 m^2, at an element size of 0.334557 m. Its 2.8e-8 m height is round-off 2 m from the
// origin (below 2.4e-7 x 2 m): skipped. Ten times as high (aspect 1e6) and at the origin it is a
// face, which the cut's bound (no piece shorter than 1/32 of the element size) keeps to one row
// for each of its two strips, where a cut to 4:1 alone would make 235,000 rows.
TEST(MessyFaces, TheBookTriangleOfTheFurnishedRoomIsSkippedAndItsShapeBounded) {
    const float height = float(2.0 * 3.6e-9 / 0.26);
    SceneArrays s;
    s.add_polygon({{2, 0, 0}, {2.26f, 0, 0}, {2.1f, height, 0}}, Rgb(0.5), Rgb(0));
    const BuildResult r = build_elements(s.input(), 0.334557f, sliver_limits());
    ASSERT_EQ(r.skipped.size(), 1u);
    EXPECT_EQ(r.skipped[0].defect, Defect::ZeroArea);
    EXPECT_EQ(r.elements.size(), 0u);
    EXPECT_EQ(elements_of({{0, 0, 0}, {0.26f, 0, 0}, {0.1f, 10 * height, 0}}, 0.334557f, sliver_limits()), 2u);
}

// Zero-area triangles and collinear ones up to 1 m long, in float as meshes hold them: skipped,
// each reported as ZeroArea, beside an ordinary face that is cut as it would be alone.
TEST(MessyFaces, FacesWithoutAreaAreSkippedAndReported) {
    SceneArrays s;
    s.add_quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, Rgb(0.5));
    s.add_polygon({{0.5f, 0.5f, 0}, {0.5f, 0.5f, 0}, {0.5f, 0.5f, 0}}, Rgb(0.5), Rgb(0));  // one point
    for (const float length : {1e-3f, 0.1f, 1.0f}) {
        const Vec3 along = Vec3(0.3f, 0.2f, 0.1f) * length;
        s.add_polygon({{0, 0, 0}, along, 3.0f * along}, Rgb(0.5), Rgb(0));
    }
    const BuildResult r = build_elements(s.input(), kSize, sliver_limits());
    ASSERT_EQ(r.skipped.size(), 4u);
    for (std::size_t k = 0; k < r.skipped.size(); ++k) {
        EXPECT_EQ(r.skipped[k].polygon, int32_t(k + 1));
        EXPECT_EQ(r.skipped[k].defect, Defect::ZeroArea);
    }
    EXPECT_EQ(r.elements.size(), 16u);
}

// Corners in a line 1 m from the origin, rounded to float: a height of round-off (below two float
// units of the coordinates, 2.4e-7 m here), whatever the length, is no area: skipped. A sliver
// 1 um high there is a face.
TEST(MessyFaces, AHeightOfRoundOffIsNoArea) {
    SceneArrays s;
    const Vec3 from(1.0f, 1.0f, 1.0f), along(0.8f, 0.6f, 0.0f);
    for (const float length : {1e-3f, 0.1f})
        s.add_polygon({from, from + 0.37f * length * along, from + length * along}, Rgb(0.5), Rgb(0));
    s.add_polygon({from, from + along, from + 0.3f * along + Vec3(0, 0, 1e-6f)}, Rgb(0.5), Rgb(0));
    const BuildResult r = build_elements(s.input(), kSize, sliver_limits());
    ASSERT_EQ(r.skipped.size(), 2u);
    EXPECT_EQ(r.skipped[0].polygon, 0);
    EXPECT_EQ(r.skipped[1].polygon, 1);
    for (std::size_t e = 0; e < r.elements.size(); ++e) EXPECT_EQ(r.elements.polygon[e], 2);
    EXPECT_EQ(r.elements.size(), 5u);  // a cap, strips of 0.3 m and 0.7 m: 2 + 3 rows
}
