/// @file test_scene.cpp
/// @brief build_elements: validation, defect reports, n-gon splitting, subdivision limits, area.

#include "geometry/scene.h"
#include "testing/test_util.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <cmath>
#include <limits>
#include <numeric>

using namespace radiosity;
using test::SceneArrays;

namespace {

double total_area(const Elements& e) { return std::accumulate(e.area.begin(), e.area.end(), 0.0); }

float longest_edge(const Elements& e) {
    float longest = 0.0f;
    for (const auto& c : e.corners) {
        const int k = c[3] < 0 ? 3 : 4;
        for (int i = 0; i < k; ++i)
            longest = std::max(longest, glm::length(e.vertices[c[(i + 1) % k]] - e.vertices[c[i]]));
    }
    return longest;
}

/// An L-shaped hexagon in z = 0 (concave at (1, 1)), area 3. It starts at a corner from which a
/// triangle fan would leave the outline.
std::vector<Vec3> l_shape() { return {{1, 2, 0}, {0, 2, 0}, {0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}}; }

}  // namespace

TEST(Scene, OneElementPerPolygonWhenMaxEdgeIsZero) {
    const SceneArrays s = test::cornell_box();
    const BuildResult r = build_elements(s.input(), 0.0f);
    EXPECT_TRUE(r.skipped.empty());
    // One element per polygon, then the back side of the emitting one (the light).
    ASSERT_EQ(test::front_count(r.elements), s.material.size());
    ASSERT_EQ(r.elements.size(), s.material.size() + 1);
    for (std::size_t e = 0; e < r.elements.size(); ++e) {
        EXPECT_EQ(r.elements.polygon[e], e < s.material.size() ? static_cast<int32_t>(e) : r.elements.polygon.back());
        EXPECT_NEAR(glm::length(r.elements.normal[e]), 1.0f, 1e-6f);
    }
    EXPECT_NEAR(r.elements.area[0], 1.0f, 1e-6f);
    EXPECT_EQ(r.elements.normal[0], Vec3(0, 0, 1));
    EXPECT_EQ(r.elements.centre[0], Vec3(0.5f, 0.5f, 0.0f));
    for (std::size_t c = 0; c < s.corner_vertices.size(); ++c) {
        const float* expected = &s.positions[3 * s.corner_vertices[c]];
        EXPECT_EQ(r.elements.vertices[r.elements.corner_vertex[c]], Vec3(expected[0], expected[1], expected[2]));
    }
}

TEST(Scene, SubdivisionKeepsEdgesShortAndAreaWhole) {
    const SceneArrays s = test::cornell_box();
    const double area = total_area(build_elements(s.input(), 0.0f).elements);
    for (float max_edge : {0.3f, 0.1f, 0.05f}) {
        const BuildResult r = build_elements(s.input(), max_edge);
        EXPECT_LE(longest_edge(r.elements), max_edge * (1.0f + 1e-5f));
        EXPECT_NEAR(total_area(r.elements), area, 1e-5 * area);
    }
    // A unit quad at 0.25 is exactly a 4 x 4 grid sharing its 25 vertices.
    const BuildResult r = build_elements(test::closed_box(Vec3(1), Rgb(0.5), Rgb(0)).input(), 0.25f);
    EXPECT_EQ(r.elements.size(), 6u * 16u);
    EXPECT_EQ(r.elements.vertices.size(), 6u * 25u);
}

TEST(Scene, TrianglesSubdivideRegularly) {
    SceneArrays s;
    s.add_polygon({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, Rgb(0.5), Rgb(0));
    const BuildResult r = build_elements(s.input(), 0.5f);
    // Longest edge sqrt(2) needs 3 segments: 9 triangles, 10 shared grid vertices.
    EXPECT_EQ(r.elements.size(), 9u);
    EXPECT_EQ(r.elements.vertices.size(), 10u);
    EXPECT_LE(longest_edge(r.elements), 0.5f);
    EXPECT_NEAR(total_area(r.elements), 0.5, 1e-6);
    for (std::size_t e = 0; e < r.elements.size(); ++e) {
        EXPECT_TRUE(r.elements.is_triangle(e));
        EXPECT_NEAR(r.elements.normal[e].z, 1.0f, 1e-6f);
    }
}

TEST(Scene, ConcaveNgonIsSplitIntoConvexPiecesInsideIt) {
    // The L of three unit squares: two convex quads, each cut by its own counts.
    SceneArrays s;
    s.add_polygon(l_shape(), Rgb(0.5), Rgb(0));
    for (float max_edge : {0.0f, 0.3f}) {
        const BuildResult r = build_elements(s.input(), max_edge);
        EXPECT_TRUE(r.skipped.empty());
        EXPECT_NEAR(total_area(r.elements), 3.0, 1e-5);
        for (std::size_t e = 0; e < r.elements.size(); ++e) {
            EXPECT_FALSE(r.elements.is_triangle(e));
            EXPECT_NEAR(r.elements.normal[e].z, 1.0f, 1e-6f);  // none flipped: all inside the outline
            const Vec3 c = r.elements.centre[e];
            EXPECT_FALSE(c.x > 1.0f && c.y > 1.0f) << "element outside the L at " << c.x << ", " << c.y;
        }
        if (max_edge > 0.0f) {
            EXPECT_LE(longest_edge(r.elements), max_edge * (1.0f + 1e-5f));
            // Trapezoids cut along the diagonal from the inner corner: 5 x 7 each, against 34
            // squares of 0.3 m covering 3 m^2.
            EXPECT_EQ(r.elements.size(), 70u);
        } else {
            EXPECT_EQ(r.elements.size(), 2u);
        }
    }
}

TEST(Scene, AShortArmIsNotCutAsFinelyAsTheLongOne) {
    // An L-shaped rug, a 1.2 m arm and a 0.4 m one, 0.4 m wide: at 6.25 cm every element is near
    // that size (one count for all its ear triangles cut the short arm's 0.4 m edges 20 times).
    SceneArrays s;
    s.add_polygon({{0, 0, 0}, {1.2f, 0, 0}, {1.2f, 0.4f, 0}, {0.4f, 0.4f, 0}, {0.4f, 1.2f, 0}, {0, 1.2f, 0}}, Rgb(0.5),
                  Rgb(0));
    const float max_edge = 0.0625f;
    const BuildResult r = build_elements(s.input(), max_edge);
    EXPECT_NEAR(total_area(r.elements), 0.8, 1e-5);
    // Two convex pieces (trapezoids, cut along the diagonal from the inner corner): about twice the
    // elements of max_edge squares covering the area (205), none smaller than 0.4 of such a square.
    EXPECT_LE(r.elements.size(), 2u * 205u);
    float smallest = 1e9f;
    for (const float a : r.elements.area) smallest = std::min(smallest, a);
    EXPECT_GT(smallest, 0.4f * max_edge * max_edge);
}

TEST(Scene, DegeneratePolygonsAreReportedNotUsed) {
    SceneArrays s;
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    s.add_quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, Rgb(0.5));    // 0: fine
    s.add_quad({0, 0, 0}, {1, 0, 0}, {nan, 1, 0}, {0, 1, 0}, Rgb(0.5));  // 1: NaN
    s.add_polygon({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, Rgb(0.5), Rgb(0));  // 2: collinear
    s.add_quad({0, 0, 0}, {1, 0, 0}, {1, inf, 0}, {0, 1, 0}, Rgb(0.5));  // 3: infinite
    s.add_polygon({{0, 0, 0}, {1, 0, 0}}, Rgb(0.5), Rgb(0));             // 4: two corners
    s.add_polygon({{0, 0, 1}, {1, 0, 1}, {1, 1, 1}}, Rgb(0.5), Rgb(0));  // 5: fine
    s.corner_vertices.back() = 1000;                                     //    ... now a bad index
    const BuildResult r = build_elements(s.input(), 0.0f);
    ASSERT_EQ(r.skipped.size(), 5u);
    EXPECT_EQ(r.skipped[0].polygon, 1);
    EXPECT_EQ(r.skipped[0].defect, Defect::NonFinite);
    EXPECT_EQ(r.skipped[1].polygon, 2);
    EXPECT_EQ(r.skipped[1].defect, Defect::ZeroArea);
    EXPECT_EQ(r.skipped[2].polygon, 3);
    EXPECT_EQ(r.skipped[2].defect, Defect::NonFinite);
    EXPECT_EQ(r.skipped[3].polygon, 4);
    EXPECT_EQ(r.skipped[3].defect, Defect::TooFewCorners);
    EXPECT_EQ(r.skipped[4].polygon, 5);
    EXPECT_EQ(r.skipped[4].defect, Defect::BadIndex);
    ASSERT_EQ(r.elements.size(), 1u);
    EXPECT_EQ(r.elements.polygon[0], 0);
    for (std::size_t c = 4; c < s.corner_vertices.size(); ++c) EXPECT_EQ(r.elements.corner_vertex[c], -1);
}

TEST(Scene, InconsistentArraysThrowNamingThePolygon) {
    auto message_of = [](const SceneArrays& s) {
        try {
            build_elements(s.input(), 0.0f);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no exception");
    };
    SceneArrays s = test::cornell_box();
    s.reflectance[3 * 4 + 1] = 1.0f;
    EXPECT_NE(message_of(s).find("polygon 4"), std::string::npos) << message_of(s);
    EXPECT_NE(message_of(s).find("reflectance"), std::string::npos);

    s = test::cornell_box();
    s.emission[3 * 7] = -1.0f;
    EXPECT_NE(message_of(s).find("polygon 7: emission"), std::string::npos) << message_of(s);
    s.emission[3 * 7] = std::numeric_limits<float>::infinity();
    EXPECT_NE(message_of(s).find("polygon 7: emission"), std::string::npos) << message_of(s);

    s = test::cornell_box();
    std::swap(s.face_offsets[3], s.face_offsets[4]);
    EXPECT_NE(message_of(s).find("polygon 3: face offsets"), std::string::npos) << message_of(s);
}
