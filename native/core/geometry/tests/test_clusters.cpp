/// @file test_clusters.cpp
/// @brief Solve elements chosen by the element size, not the faces: a finely tessellated surface
/// merges to as many elements as a coarse one, and only like, coplanar, unlit-by-itself faces merge.
#include "geometry/clusters.h"

#include "testing/test_util.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>

namespace radiosity {
namespace {

constexpr float kSize = 0.25f;  // the element size: a 1 m square is 4 x 4 elements

Clusters clusters_of(const test::SceneArrays& scene, BuildResult& build) {
    build = build_elements(scene.input(), kSize);
    return cluster_elements(build.elements, scene.input(), kSize);
}

/// Whether point p lies in solve element s (its plane, and inside every edge), within `slack` metres.
bool inside(const Elements& solve, std::size_t s, const Vec3& p, float slack) {
    const Vec3 n = solve.normal[s];
    if (std::abs(glm::dot(p - solve.vertices[solve.corners[s][0]], n)) > slack) return false;
    const int m = solve.corner_count(s);
    for (int k = 0; k < m; ++k) {
        const Vec3 a = solve.vertices[solve.corners[s][k]], b = solve.vertices[solve.corners[s][(k + 1) % m]];
        if (glm::dot(glm::cross(b - a, p - a), n) < -slack * glm::length(b - a)) return false;
    }
    return true;
}

/// A unit square floor as cells x cells faces: the solve has the coarse square's 16 elements at
/// every density, each a quad of the element size, covering the output elements it holds.
TEST(Clusters, SubdividedSquareMergesToTheCoarseElements) {
    for (const int cells : {4, 8, 16, 32, 64}) {
        test::SceneArrays floor;
        floor.add_grid(Vec3(0.0f), Vec3(1, 0, 0), Vec3(0, 1, 0), cells, Rgb(0.5));
        BuildResult build;
        const Clusters clusters = clusters_of(floor, build);
        ASSERT_EQ(build.elements.size(), std::size_t(cells * cells));
        if (cells == 4) {
            EXPECT_FALSE(clusters.merged()) << "faces of the element size stay as they are";
            continue;
        }
        ASSERT_TRUE(clusters.merged());
        const Elements& solve = clusters.elements;
        ASSERT_EQ(solve.size(), 16u) << cells;
        double area = 0.0;
        for (std::size_t s = 0; s < solve.size(); ++s) {
            ASSERT_FALSE(solve.is_triangle(s));
            EXPECT_NEAR(solve.area[s], kSize * kSize, 1e-6);
            EXPECT_NEAR(solve.normal[s].z, 1.0, 1e-6);
            area += solve.area[s];
        }
        EXPECT_NEAR(area, 1.0, 1e-5);
        for (std::size_t e = 0; e < build.elements.size(); ++e)
            ASSERT_TRUE(inside(solve, std::size_t(clusters.of_element[e]), build.elements.centre[e], 1e-6f)) << e;
    }
}

/// The faces in a scrambled order (a mesh's faces come in whatever order modelling left them):
/// the clusters still follow the lattice of the element size, 16 of them.
TEST(Clusters, ScrambledFacesMergeToTheCoarseElements) {
    for (const int cells : {16, 32, 64}) {
        test::SceneArrays grid;
        grid.add_grid(Vec3(0.3f, -0.2f, 0.7f), Vec3(1, 0, 0), Vec3(0, 1, 0), cells, Rgb(0.5));
        test::SceneArrays floor;
        const int faces = cells * cells;
        for (int i = 0; i < faces; ++i) {
            const int f = int((std::int64_t(i) * 7919) % faces);  // 7919 is prime: a permutation
            std::vector<Vec3> corners;
            for (int c = grid.face_offsets[f]; c < grid.face_offsets[f + 1]; ++c) {
                const float* p = &grid.positions[3 * std::size_t(grid.corner_vertices[std::size_t(c)])];
                corners.emplace_back(p[0], p[1], p[2]);
            }
            floor.add_polygon(corners, Rgb(0.5), Rgb(0.0));
        }
        BuildResult build;
        const Clusters clusters = clusters_of(floor, build);
        EXPECT_EQ(clusters.elements.size(), 16u) << cells;
    }
}

/// Each face cut into two triangles: pairs become quads, which merge as before.
TEST(Clusters, TriangulatedSquareMergesToTheCoarseElements) {
    for (const int cells : {16, 32}) {
        test::SceneArrays floor;
        auto at = [&](int i, int j) { return Vec3(float(i) / float(cells), float(j) / float(cells), 0.0f); };
        for (int i = 0; i < cells; ++i)
            for (int j = 0; j < cells; ++j) {
                floor.add_polygon({at(i, j), at(i + 1, j), at(i + 1, j + 1)}, Rgb(0.5), Rgb(0.0));
                floor.add_polygon({at(i, j), at(i + 1, j + 1), at(i, j + 1)}, Rgb(0.5), Rgb(0.0));
            }
        BuildResult build;
        const Clusters clusters = clusters_of(floor, build);
        ASSERT_EQ(build.elements.size(), std::size_t(2 * cells * cells));
        ASSERT_TRUE(clusters.merged());
        EXPECT_EQ(clusters.elements.size(), 16u) << cells;
        double area = 0.0;
        for (const float a : clusters.elements.area) area += a;
        EXPECT_NEAR(area, 1.0, 1e-5);
    }
}

/// Faces merge only with faces of the same surface in the same plane: not across a change of
/// reflectance, material or emission, nor over a fold; an emitter's fronts merge with fronts and its
/// back sides with back sides, the fronts staying before the back sides.
TEST(Clusters, UnlikeFacesStaySeparate) {
    const int cells = 16;  // faces of 1/16 m: 4 x 4 of them make an element
    {
        test::SceneArrays halves;  // two reflectances, a material change and an emitting strip
        halves.add_grid(Vec3(0.0f), Vec3(0.5f, 0, 0), Vec3(0, 1, 0), cells / 2, Rgb(0.5));
        halves.add_grid(Vec3(0.5f, 0, 0), Vec3(0.5f, 0, 0), Vec3(0, 1, 0), cells / 2, Rgb(0.3));
        halves.add_grid(Vec3(1.0f, 0, 0), Vec3(0.5f, 0, 0), Vec3(0, 1, 0), cells / 2, Rgb(0.3), Rgb(0.0), 7);
        halves.add_grid(Vec3(1.5f, 0, 0), Vec3(0.5f, 0, 0), Vec3(0, 1, 0), cells / 2, Rgb(0.3), Rgb(1.0));
        BuildResult build;
        const Clusters clusters = clusters_of(halves, build);
        ASSERT_TRUE(clusters.merged());
        // 4 merged blocks of 2 x 4 elements, the emitting one's fronts and back sides apart.
        EXPECT_EQ(clusters.elements.size(), 3u * 8u + 2u * 8u);
        std::size_t last_front = 0, first_back = clusters.elements.size();
        for (std::size_t s = 0; s < clusters.elements.size(); ++s) {
            if (clusters.elements.side[s] == Elements::kFront) last_front = s;
            if (clusters.elements.side[s] == Elements::kBack) first_back = std::min(first_back, s);
        }
        EXPECT_LT(last_front, first_back);
        for (std::size_t e = 0; e < build.elements.size(); ++e) {
            const std::size_t s = std::size_t(clusters.of_element[e]);
            EXPECT_EQ(clusters.elements.reflectance[s], build.elements.reflectance[e]);
            EXPECT_EQ(halves.material[std::size_t(clusters.elements.polygon[s])],
                      halves.material[std::size_t(build.elements.polygon[e])]);
            EXPECT_EQ(clusters.elements.emission[s], build.elements.emission[e]);
            EXPECT_EQ(clusters.elements.side[s], build.elements.side[e]);
        }
    }
    {
        test::SceneArrays fold;  // a floor and a wall meeting at an edge: no cluster bends over it
        fold.add_grid(Vec3(0.0f), Vec3(1, 0, 0), Vec3(0, 0.5f, 0), cells, Rgb(0.5));
        fold.add_grid(Vec3(0, 0.5f, 0), Vec3(1, 0, 0), Vec3(0, 0.5f, 0.5f), cells, Rgb(0.5));
        BuildResult build;
        const Clusters clusters = clusters_of(fold, build);
        ASSERT_TRUE(clusters.merged());
        for (std::size_t e = 0; e < build.elements.size(); ++e)
            EXPECT_GT(glm::dot(clusters.elements.normal[std::size_t(clusters.of_element[e])], build.elements.normal[e]),
                      0.9999f);
    }
}

/// A block standing on a finely tessellated floor: the contact cut runs through the floor's faces
/// (its outline is off their grid). Elements along the cut merge, but no cluster reaches over it:
/// each holds floor inside the footprint or outside it, never both.
TEST(Clusters, ClustersNeverStraddleAContactLine) {
    test::SceneArrays scene;
    scene.add_grid(Vec3(0.0f), Vec3(1, 0, 0), Vec3(0, 1, 0), 32, Rgb(0.5));
    const float lo = 0.3f, hi = 0.55f, top = 0.2f;
    scene.add_quad({lo, lo, top}, {hi, lo, top}, {hi, hi, top}, {lo, hi, top}, Rgb(0.5));  // top, +z
    scene.add_quad({lo, lo, 0}, {hi, lo, 0}, {hi, lo, top}, {lo, lo, top}, Rgb(0.5));      // -y side
    scene.add_quad({hi, lo, 0}, {hi, hi, 0}, {hi, hi, top}, {hi, lo, top}, Rgb(0.5));      // +x side
    scene.add_quad({hi, hi, 0}, {lo, hi, 0}, {lo, hi, top}, {hi, hi, top}, Rgb(0.5));      // +y side
    scene.add_quad({lo, hi, 0}, {lo, lo, 0}, {lo, lo, top}, {lo, hi, top}, Rgb(0.5));      // -x side
    const BuildResult build = build_elements(scene.input(), kSize, ElementLimits().with_contacts());
    const Elements& output = build.elements;
    const Clusters clusters = cluster_elements(output, scene.input(), kSize);
    ASSERT_TRUE(clusters.merged());
    auto under_block = [&](const Vec3& p) { return p.x > lo && p.x < hi && p.y > lo && p.y < hi; };
    std::vector<int> inside(clusters.elements.size(), 0), outside(clusters.elements.size(), 0), members = inside;
    std::size_t cut_elements = 0, merged_cut_elements = 0;
    for (std::size_t e = 0; e < output.size(); ++e) {
        if (output.centre[e].z > 1e-6f) continue;  // the floor only
        const std::size_t s = std::size_t(clusters.of_element[e]);
        (under_block(output.centre[e]) ? inside : outside)[s] += 1;
        ++members[s];
        if (output.cut_edges[e] != 0) ++cut_elements;
    }
    for (std::size_t e = 0; e < output.size(); ++e)
        if (output.centre[e].z < 1e-6f && output.cut_edges[e] != 0 && members[std::size_t(clusters.of_element[e])] > 1)
            ++merged_cut_elements;
    for (std::size_t s = 0; s < clusters.elements.size(); ++s)
        EXPECT_TRUE(inside[s] == 0 || outside[s] == 0) << s << ": " << inside[s] << " inside, " << outside[s];
    std::printf("floor elements on the contact line: %zu, of which %zu merged\n", cut_elements, merged_cut_elements);
    EXPECT_GT(cut_elements, 0u);
    EXPECT_GT(merged_cut_elements, cut_elements / 2);
}

/// A floor of small faces with a point lamp 10 cm over it: every cluster's edges are at most half
/// its members' distance from the lamp, so faces within twice their size of it keep their own solve
/// elements, clusters grow with the distance, and far from the lamp they reach the element size as
/// without it.
TEST(Clusters, ClustersBesideAPointLampAreNoLongerThanHalfTheirDistance) {
    test::SceneArrays floor;
    floor.add_grid(Vec3(0.0f), Vec3(2, 0, 0), Vec3(0, 2, 0), 32, Rgb(0.5));  // faces of 6.25 cm
    const BuildResult build = build_elements(floor.input(), kSize);
    const Vec3 lamp(0.5f, 0.5f, 0.1f);
    const Clusters lit = cluster_elements(build.elements, floor.input(), kSize, {lamp});
    const Clusters unlit = cluster_elements(build.elements, floor.input(), kSize);
    ASSERT_TRUE(lit.merged());
    const Elements& solve = lit.elements;
    std::vector<float> nearest(solve.size(), 1e9f);
    std::vector<int> members(solve.size(), 0);
    for (std::size_t e = 0; e < build.elements.size(); ++e) {
        const auto s = std::size_t(lit.of_element[e]);
        nearest[s] = std::min(nearest[s], glm::distance(build.elements.centre[e], lamp));
        ++members[s];
    }
    int single_near = 0, far_full = 0;
    for (std::size_t s = 0; s < solve.size(); ++s) {
        float longest = 0.0f;
        for (int k = 0; k < solve.corner_count(s); ++k)
            longest =
                std::max(longest, glm::distance(solve.vertices[solve.corners[s][k]],
                                                solve.vertices[solve.corners[s][(k + 1) % solve.corner_count(s)]]));
        if (members[s] > 1) EXPECT_LE(longest, 0.5f * nearest[s] * 1.001f) << s;
        if (nearest[s] < 2.0f * 0.0625f) {
            EXPECT_EQ(members[s], 1) << s;
            ++single_near;
        }
        if (nearest[s] > 2.0f * kSize && longest > 0.99f * kSize) ++far_full;
    }
    EXPECT_GE(single_near, 4);              // the faces under the lamp
    EXPECT_GT(far_full, 40);                // most of the 64 element-sized squares of the unlit floor
    EXPECT_EQ(unlit.elements.size(), 64u);  // the 2 m floor in elements of the element size
    EXPECT_GT(lit.elements.size(), unlit.elements.size());
    EXPECT_LT(lit.elements.size(), build.elements.size() / 4);  // clusters of more than 4 faces on average
}

/// No element size (one element per polygon): nothing merges.
TEST(Clusters, NoElementSizeNoMerge) {
    test::SceneArrays floor;
    floor.add_grid(Vec3(0.0f), Vec3(1, 0, 0), Vec3(0, 1, 0), 8, Rgb(0.5));
    const BuildResult build = build_elements(floor.input(), 0.0f);
    EXPECT_FALSE(cluster_elements(build.elements, floor.input(), 0.0f).merged());
}

}  // namespace
}  // namespace radiosity
