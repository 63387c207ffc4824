/// @file test_hierarchy.cpp
/// @brief Hierarchical radiosity against exact answers: a furnace, analytic factors, a point
/// lamp's direct light and shadow, the uniform bake of the same scene; and its mesh, clusters,
/// cap and cancel.
#include "bake/bake.h"
#include "hierarchy/hierarchy.h"
#include "testing/test_util.h"
#include "transport/near_field.h"

#include <gtest/gtest.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <limits>
#include <map>

namespace radiosity {
namespace {

HierarchySettings settings(float min_size, double refine_tolerance) {
    HierarchySettings s;
    s.min_element_size = min_size;
    s.refine_tolerance = refine_tolerance;
    s.tolerance = 1e-7;
    s.max_rounds = 40;
    return s;
}

/// `s` with a point lamp of unit intensity at `position`.
HierarchySettings with_lamp(HierarchySettings s, const Vec3& position) {
    PointLight lamp;
    lamp.position = position;
    lamp.intensity = Rgb(1.0);
    s.lights.points.push_back(lamp);
    return s;
}

/// Area-weighted mean radiance (red) of each input polygon's fronts.
std::map<int32_t, double> polygon_means(const Elements& e, const std::vector<Rgb>& radiance) {
    std::map<int32_t, double> power, area;
    for (std::size_t i = 0; i < e.size(); ++i) {
        if (e.is_back(i)) continue;  // the fronts, whose colours are written
        power[e.polygon[i]] += radiance[i].r * e.area[i];
        area[e.polygon[i]] += e.area[i];
    }
    for (auto& [p, value] : power) value /= area[p];
    return power;
}

TEST(Hierarchy, FurnaceIsUniformAtTheExactValue) {
    // Closed box, rho = 0.8, E = 1: L = E / (1 - rho) = 5 everywhere, however the box is meshed,
    // if every leaf's factors sum to 1 (links at many levels, near field at the edges).
    const auto box = test::closed_box(Vec3(1, 2, 3), Rgb(0.8), Rgb(1.0));
    const HierarchyResult r = bake_hierarchical(box.input(), settings(0.05f, 0.005));
    ASSERT_TRUE(r.converged);
    ASSERT_GT(r.stats.leaves, 6u);
    // The walls' back sides (emitting polygons are two-sided) face out of the box: L = E.
    for (std::size_t i = 0; i < r.output.size(); ++i)
        if (r.output.is_back(i)) EXPECT_NEAR(r.output_radiance[i].r, 1.0, 1e-9) << i;
    for (const Rgb& L : test::fronts(r.output, r.output_radiance)) EXPECT_NEAR(L.r, 5.0, 0.05);
}

TEST(Hierarchy, OpposedSquaresMatchTheAnalyticFactor) {
    // A black emitter (L = 1) over a receiver with rho = 0.5: L_r = rho F, no further bounce.
    // F = 0.19982 for unit squares one apart (Howell, C-11).
    auto squares = test::opposed_unit_squares(1.0f, Rgb(0.5), Rgb(1.0));
    for (int k = 0; k < 3; ++k) squares.reflectance[k] = 0.0f;  // the emitter reflects nothing
    const HierarchyResult r = bake_hierarchical(squares.input(), settings(0.05f, 0.01));
    EXPECT_NEAR(polygon_means(r.output, r.output_radiance).at(1), 0.5 * 0.19982, 0.5 * 0.19982 * 2e-3);
}

TEST(Hierarchy, PointLampLightsTheFloorExactlyAndRefinesAtTheShadowEdge) {
    // A 2 m floor under a lamp 1 m up, a small black card halfway between casting a shadow.
    test::SceneArrays scene;
    scene.add_quad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, Rgb(0.5));
    scene.add_quad({-0.1f, -0.1f, 0.5f}, {-0.1f, 0.1f, 0.5f}, {0.1f, 0.1f, 0.5f}, {0.1f, -0.1f, 0.5f}, Rgb(0.0));
    const HierarchySettings s = with_lamp(settings(0.01f, 0.003), Vec3(0, 0, 1));
    const PointLight& lamp = s.lights.points[0];
    const HierarchyResult r = bake_hierarchical(scene.input(), s);

    // The card's shadow on the floor is the square |x|, |y| < 0.2 (twice the card: half-way up).
    // What the artist sees are the corner colours: they must match rho I cos / (pi r^2) at the
    // corners, wherever the element is off the shadow's edge (coarse ones included: there the
    // light varies nearly linearly, and corners interpolate that).
    auto to_shadow_edge = [](const Vec3& p) { return std::abs(std::max(std::abs(p.x), std::abs(p.y)) - 0.2f); };
    float edge_size = 0.0f, far_size = 0.0f;
    std::size_t checked = 0;
    for (std::size_t e = 0; e < r.output.size(); ++e) {
        if (r.output.polygon[e] != 0) continue;
        // The floor sees only the lamp (the card is black): all its light is the lamp's first
        // reflection, which the output counts as emitted (for the energy account).
        EXPECT_NEAR(r.output.emission[e].r, r.output_radiance[e].r, 1e-12);
        const float size = std::sqrt(r.output.area[e]);
        const float to_edge = to_shadow_edge(r.output.centre[e]);
        if (to_edge < 0.02f) edge_size = std::max(edge_size, size);
        if (to_edge > 0.5f) far_size = std::max(far_size, size);
        if (to_edge < 2.0f * size) continue;  // its corners blend with elements across the edge
        for (int k = 0; k < (r.output.is_triangle(e) ? 3 : 4); ++k) {
            const Vec3 p = r.output.vertices[r.output.corners[e][k]];
            if (std::max(std::abs(p.x), std::abs(p.y)) > 0.99f) continue;  // the floor's border
            const bool shadowed = std::max(std::abs(p.x), std::abs(p.y)) < 0.2f;
            const float r2 = glm::dot(p - lamp.position, p - lamp.position);
            const double exact = shadowed ? 0.0 : 0.5 * (1.0 / std::sqrt(r2)) / (M_PI * r2);
            EXPECT_NEAR(r.colors.element_corner[4 * e + k].r, exact, 0.02 * 0.5 / M_PI)
                << "corner " << p.x << ", " << p.y;
            ++checked;
        }
    }
    EXPECT_GT(checked, 100u);
    // Elements are fine along the shadow's edge and coarse far from it.
    EXPECT_LE(edge_size, 0.03f);
    EXPECT_GE(far_size, 4.0f * edge_size);
}

TEST(Hierarchy, SunLightsAFloorUniformlyExceptInTheShadowOfABlock) {
    // Sun at 60 degrees from the zenith, irradiance 2 on a plane facing it: a bare floor gets
    // L = rho E cos / pi everywhere the block does not shade (exact: no other surface lights it).
    test::SceneArrays scene;
    scene.add_quad({-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}, Rgb(0.5));
    scene.add_quad({-0.2f, -0.2f, 0.5f}, {-0.2f, 0.2f, 0.5f}, {0.2f, 0.2f, 0.5f}, {0.2f, -0.2f, 0.5f}, Rgb(0.0));
    HierarchySettings s = settings(0.05f, 0.01);
    SunLight sun;
    const float zenith = float(M_PI) / 3.0f;
    sun.direction = Vec3(std::sin(zenith), 0.0f, -std::cos(zenith));  // travelling towards +x, down
    sun.irradiance = Rgb(2.0);
    s.lights.suns.push_back(sun);
    const HierarchyResult r = bake_hierarchical(scene.input(), s);
    // The card at z = 0.5 casts its shadow 0.5 tan(60 deg) = 0.87 m towards +x.
    const double lit = 0.5 * 2.0 * std::cos(zenith) / M_PI;
    std::size_t checked = 0;
    for (std::size_t e = 0; e < r.output.size(); ++e) {
        if (r.output.polygon[e] != 0) continue;
        const Vec3 c = r.output.centre[e];
        const float margin = std::sqrt(r.output.area[e]);
        const float x = c.x - 0.866f;  // the shadow's centre
        const bool inside = std::abs(x) < 0.2f - margin && std::abs(c.y) < 0.2f - margin;
        const bool outside = std::abs(x) > 0.2f + margin || std::abs(c.y) > 0.2f + margin;
        if (inside) EXPECT_NEAR(r.output_radiance[e].r, 0.0, 1e-12) << c.x << ", " << c.y;
        if (outside) EXPECT_NEAR(r.output_radiance[e].r, lit, 1e-6 * lit) << c.x << ", " << c.y;
        checked += inside || outside;
    }
    EXPECT_GT(checked, 100u);
}

TEST(Hierarchy, LampLightAtTheCornersIsExactOnACoarseMesh) {
    // A bare 2 m floor 1 m under a lamp, in 1 m leaves: the lamp's light varies by 3x over it,
    // and leaf means interpolated to the corners would miss it by tens of percent. The corners
    // show rho I cos / (pi r^2) as it is at each one (nothing else lights the floor).
    test::SceneArrays scene;
    scene.add_quad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, Rgb(0.5));
    HierarchySettings s = with_lamp(settings(1.0f, 0.01), Vec3(0.3f, 0.2f, 1.0f));
    s.lamp_detail_levels = 0;
    const HierarchyResult r = bake_hierarchical(scene.input(), s);
    ASSERT_EQ(r.output.size(), 4u);
    EXPECT_EQ(r.stats.lamp_splits, 0u);
    for (std::size_t e = 0; e < r.output.size(); ++e)
        for (int k = 0; k < 4; ++k) {
            const Vec3 d = s.lights.points[0].position - r.output.vertices[r.output.corners[e][k]];
            const double r2 = glm::dot(d, d), exact = 0.5 * (d.z / std::sqrt(r2)) / (M_PI * r2);
            EXPECT_NEAR(r.colors.element_corner[4 * e + k].r, exact, 1e-3 * exact)
                << "element " << e << " corner " << k;
        }
}

/// Form factor from a point to a parallel a x b rectangle at height c, the point under one of
/// its corners (Howell's catalogue, B-11).
double point_under_rectangle_corner(double a, double b, double c) {
    const double A = a / c, B = b / c, sa = std::sqrt(1 + A * A), sb = std::sqrt(1 + B * B);
    return (A / sa * std::atan(B / sa) + B / sb * std::atan(A / sb)) / (2 * M_PI);
}

TEST(Hierarchy, EmitterLightAtTheCornersFollowsThePointFactor) {
    // A 1 m floor under a 1 m emitting square 0.5 m up, each one leaf: the floor's corners see
    // the emitter at half the factor its centre does. Its one leaf's mean interpolated to the
    // corners would show them twice too bright; each corner shows rho L F(corner) instead.
    test::SceneArrays scene;
    scene.add_quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, Rgb(0.5));
    scene.add_quad({0, 0, 0.5f}, {0, 1, 0.5f}, {1, 1, 0.5f}, {1, 0, 0.5f}, Rgb(0.0), Rgb(1.0));
    const HierarchyResult r = bake_hierarchical(scene.input(), settings(0.6f, 0.01));  // 1 m cannot split
    ASSERT_EQ(r.output.size(), 3u);  // the floor, the emitter and its back side
    const double corner = 0.5 * point_under_rectangle_corner(1, 1, 0.5);
    const double mean = r.output_radiance[0].r;
    EXPECT_GT(mean, 1.8 * corner);  // what the leaf's mean alone would show
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(r.colors.element_corner[k].r, corner, 1e-3 * corner) << "corner " << k;
}

TEST(Hierarchy, EmitterShadowAtTheCornersIsTracedFromEachCorner) {
    // A 2 x 1 m floor, one leaf; an emitter 0.5 m over its left half; a black card across the
    // middle, 1 cm clear of the floor. The floor's link sees the emitter partly (its rays split);
    // from each corner the emitter is all in view (x = 0) or all hidden (x = 2), and the corners
    // show exactly that: rho L F at the left, nothing at the right.
    test::SceneArrays scene;
    scene.add_quad({0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}, Rgb(0.5));
    scene.add_quad({-0.3f, 0, 0.5f}, {-0.3f, 1, 0.5f}, {0.9f, 1, 0.5f}, {0.9f, 0, 0.5f}, Rgb(0.0), Rgb(1.0));
    scene.add_quad({1, -1, 0.01f}, {1, 2, 0.01f}, {1, 2, 1}, {1, -1, 1}, Rgb(0.0));
    const HierarchyResult r = bake_hierarchical(scene.input(), settings(1.05f, 0.01));
    ASSERT_EQ(r.output.polygon[0], 0);
    ASSERT_FALSE(r.output.is_triangle(0));
    ASSERT_TRUE(r.output.size() == 1 || r.output.polygon[1] != 0);  // the floor is one element
    const double lit = 0.5 * (point_under_rectangle_corner(0.3, 1, 0.5) + point_under_rectangle_corner(0.9, 1, 0.5));
    const double mean = r.output_radiance[0].r;
    EXPECT_GT(mean, 0.2 * lit);  // the floor's leaf gathers some of the emitter's light
    for (int k = 0; k < 4; ++k) {
        const Vec3 corner = r.output.vertices[r.output.corners[0][k]];
        const double exact = corner.x < 1 ? lit : 0.0;
        EXPECT_NEAR(r.colors.element_corner[k].r, exact, 1e-3 * lit) << "corner at x = " << corner.x;
    }
}

TEST(Hierarchy, LampShadowEdgeIsResolvedWithoutFinerLinks) {
    // The sun of the test above over a floor of 0.5 m tiles, a 0.5 x 0.6 m card 0.5 m up: leaves
    // split down to 0.25 m, then after the solve three levels further (to 1/32 m) only where the
    // sun's light departs from their corners, which is along the shadow's edge. Elsewhere every
    // corner is exact, and the links are those of a bake without this detail.
    test::SceneArrays scene;
    for (float x = -2; x < 2; x += 0.5f)
        for (float y = -2; y < 2; y += 0.5f)
            scene.add_quad({x, y, 0}, {x + 0.5f, y, 0}, {x + 0.5f, y + 0.5f, 0}, {x, y + 0.5f, 0}, Rgb(0.5));
    scene.add_quad({-0.25f, -0.3f, 0.5f}, {-0.25f, 0.3f, 0.5f}, {0.25f, 0.3f, 0.5f}, {0.25f, -0.3f, 0.5f}, Rgb(0.0));
    HierarchySettings s = settings(0.2f, 0.01);
    SunLight sun;
    const float zenith = float(M_PI) / 3.0f;
    sun.direction = Vec3(std::sin(zenith), 0.0f, -std::cos(zenith));
    sun.irradiance = Rgb(2.0);
    s.lights.suns.push_back(sun);
    s.lamp_detail_levels = 3;
    const HierarchyResult r = bake_hierarchical(scene.input(), s);
    HierarchySettings plain = s;
    plain.lamp_detail_levels = 0;
    const HierarchyResult without = bake_hierarchical(scene.input(), plain);
    EXPECT_EQ(r.stats.links, without.stats.links);
    EXPECT_GT(r.stats.lamp_splits, 0u);

    const double lit = 0.5 * 2.0 * std::cos(zenith) / M_PI;
    const float x0 = 0.616f, x1 = 1.116f, y0 = -0.3f, y1 = 0.3f;  // the shadow: the card moved 0.5 tan 60 deg
    std::size_t on_edge = 0, floor_elements = 0;
    for (std::size_t e = 0; e < r.output.size(); ++e) {
        if (r.output.polygon[e] == 64) continue;  // the card
        ++floor_elements;
        const int count = r.output.is_triangle(e) ? 3 : 4;
        Vec3 low(1e9f), high(-1e9f);
        for (int k = 0; k < count; ++k) {
            low = glm::min(low, r.output.vertices[r.output.corners[e][k]]);
            high = glm::max(high, r.output.vertices[r.output.corners[e][k]]);
        }
        const bool overlaps = low.x < x1 && high.x > x0 && low.y < y1 && high.y > y0;
        const bool inside = low.x >= x0 && high.x <= x1 && low.y >= y0 && high.y <= y1;
        if (overlaps && !inside) {
            ++on_edge;
            EXPECT_LE(std::max(high.x - low.x, high.y - low.y), 1.0f / 32 + 1e-4f) << low.x << ", " << low.y;
            continue;
        }
        // Off the edge, corners shared with edge elements are averaged with theirs: check the
        // element's own exact values only where it is a full element away from the edge.
        const float size = std::max(high.x - low.x, high.y - low.y);
        const bool near = low.x < x1 + size && high.x > x0 - size && low.y < y1 + size && high.y > y0 - size;
        if (near) continue;
        for (int k = 0; k < count; ++k)
            EXPECT_NEAR(r.colors.element_corner[4 * e + k].r, inside ? 0.0 : lit, 1e-5 * lit) << low.x << ", " << low.y;
    }
    // The 2.2 m outline in 1/32 m elements, less the four corners that count for two sides.
    EXPECT_GE(on_edge, std::size_t(2.2 * 32) - 4);
    // A uniform mesh of the floor at the edge's size would have 128^2 elements.
    EXPECT_LT(floor_elements, 128u * 128u / 10);
}

TEST(Hierarchy, CornellBoxAgreesWithTheUniformBake) {
    const auto cornell = test::cornell_box();
    BakeSettings uniform;
    uniform.element_size = 0.03f;
    uniform.solve.tolerance = 1e-7;
    const BakeResult reference = bake(cornell.input(), uniform);
    const auto expected = polygon_means(reference.build.elements, reference.solve.radiance);

    const HierarchyResult r = bake_hierarchical(cornell.input(), settings(0.03f, 0.01));
    const auto got = polygon_means(r.output, r.output_radiance);
    for (const auto& [polygon, value] : expected)
        EXPECT_NEAR(got.at(polygon), value, 0.04 * value) << "polygon " << polygon;
}

/// Output vertices lying strictly inside an output element's edge (T-vertices: colours crack there).
std::size_t hanging_vertices(const Elements& out) {
    std::size_t hanging = 0;
    for (std::size_t e = 0; e < out.size(); ++e) {
        const int count = out.is_triangle(e) ? 3 : 4;
        for (int k = 0; k < count; ++k) {
            const Vec3 a = out.vertices[out.corners[e][k]], b = out.vertices[out.corners[e][(k + 1) % count]];
            for (const Vec3& v : out.vertices) {
                const Vec3 ab = b - a, av = v - a;
                const float t = glm::dot(av, ab) / glm::dot(ab, ab);
                if (t > 1e-4f && t < 1.0f - 1e-4f && glm::length(av - t * ab) < 1e-6f) ++hanging;
            }
        }
    }
    return hanging;
}

TEST(Hierarchy, OutputMeshHasNoTVertices) {
    // Two polygons sharing an edge, refined differently (a lamp close to one of them): no vertex
    // may lie inside another element's edge, so colours cannot crack.
    test::SceneArrays scene;
    scene.add_quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, Rgb(0.5));
    scene.add_quad({1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, Rgb(0.5));
    const HierarchyResult r =
        bake_hierarchical(scene.input(), with_lamp(settings(0.02f, 0.01), Vec3(0.5f, 0.5f, 0.1f)));
    ASSERT_GT(r.output.size(), 50u);
    EXPECT_EQ(hanging_vertices(r.output), 0u);
    for (const Rgb& c : r.colors.element_corner) EXPECT_TRUE(std::isfinite(c.r) && c.r >= 0.0);
}

/// Twice the area of the triangle at each corner of element `e` and its two neighbours: the
/// smallest is 0 for a triangle of three points on a line or a quad with a flat corner.
double smallest_corner_area(const Elements& out, std::size_t e) {
    const int count = out.is_triangle(e) ? 3 : 4;
    double smallest = std::numeric_limits<double>::infinity();
    for (int k = 0; k < count; ++k) {
        const Vec3 a = out.vertices[out.corners[e][(k + count - 1) % count]], b = out.vertices[out.corners[e][k]],
                   c = out.vertices[out.corners[e][(k + 1) % count]];
        smallest = std::min(smallest, double(glm::length(glm::cross(a - b, c - b))));
    }
    return smallest;
}

/// The output's elements per input polygon.
std::map<int32_t, std::vector<std::size_t>> elements_by_polygon(const Elements& out) {
    std::map<int32_t, std::vector<std::size_t>> by_polygon;
    for (std::size_t e = 0; e < out.size(); ++e) by_polygon[out.polygon[e]].push_back(e);
    return by_polygon;
}

/// No degenerate element, each polygon covered exactly (`areas`: the polygons' own), no T-vertex.
void expect_conforming(const Elements& out, const std::vector<double>& areas) {
    for (const auto& [polygon, elements] : elements_by_polygon(out)) {
        double sum = 0.0;
        for (std::size_t e : elements) {
            EXPECT_GT(smallest_corner_area(out, e), 1e-3 * out.area[e]) << "element " << e;
            sum += out.area[e];
        }
        EXPECT_NEAR(sum, areas[polygon], 1e-5 * areas[polygon]) << "polygon " << polygon;
    }
    EXPECT_EQ(hanging_vertices(out), 0u);
}

TEST(Hierarchy, LeafBesideFinerOnesSplitsIntoFewElements) {
    // A lit square under a lamp splits once (0.5 m leaves are the finest); a black square beside
    // it and a black triangle on top of it stay one leaf each (they reflect nothing, so nothing
    // refines them), with the lit square's midpoint on their shared edge. Without a vertex at its
    // centre, the square needs a quad and a triangle (a fan from its centre: 5 triangles), the
    // triangle two triangles (a fan: 4).
    test::SceneArrays scene;
    scene.add_quad({1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, Rgb(0.5));
    scene.add_quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, Rgb(0.0));
    scene.add_polygon({{1, 1, 0}, {2, 1, 0}, {1.5f, 1.8f, 0}}, Rgb(0.0), Rgb(0.0));
    HierarchySettings s = with_lamp(settings(0.5f, 0.001), Vec3(1.5f, 0.5f, 0.5f));
    s.lamp_detail_levels = 0;
    const HierarchyResult r = bake_hierarchical(scene.input(), s);
    ASSERT_EQ(r.stats.leaves, 6u);
    const auto by_polygon = elements_by_polygon(r.output);
    ASSERT_EQ(by_polygon.at(0).size(), 4u);
    auto triangles = [&](int32_t polygon) {
        return std::count_if(by_polygon.at(polygon).begin(), by_polygon.at(polygon).end(),
                             [&](std::size_t e) { return r.output.is_triangle(e); });
    };
    EXPECT_EQ(by_polygon.at(1).size(), 2u);
    EXPECT_EQ(triangles(1), 1);
    EXPECT_EQ(by_polygon.at(2).size(), 2u);
    EXPECT_EQ(triangles(2), 2);
    expect_conforming(r.output, {1.0, 1.0, 0.4});
}

/// What a black square x in [0, 1] makes of the vertices a lit square x in [1, 2] puts on their
/// shared edge, baked with `s` (its output checked to conform).
struct BlackSquare {
    std::size_t edge_vertices = 0;  ///< the lit square's distinct vertices strictly inside x = 1
    std::size_t elements = 0;       ///< the black square's output elements
};

BlackSquare black_square_beside_lit_one(const HierarchySettings& s) {
    test::SceneArrays scene;
    scene.add_quad({1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, Rgb(0.5));
    scene.add_quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, Rgb(0.0));
    const HierarchyResult r = bake_hierarchical(scene.input(), s);
    expect_conforming(r.output, {1.0, 1.0});
    const auto by_polygon = elements_by_polygon(r.output);
    std::vector<float> on_edge;
    for (std::size_t e : by_polygon.at(0))
        for (int k = 0; k < (r.output.is_triangle(e) ? 3 : 4); ++k) {
            const Vec3 p = r.output.vertices[r.output.corners[e][k]];
            if (p.x == 1.0f && p.y > 0.0f && p.y < 1.0f) on_edge.push_back(p.y);
        }
    std::sort(on_edge.begin(), on_edge.end());
    return {std::size_t(std::unique(on_edge.begin(), on_edge.end()) - on_edge.begin()), by_polygon.at(1).size()};
}

TEST(Hierarchy, LeafBesideMuchFinerOnesSplitsIntoOneElementPerSegment) {
    // The black square beside a lit one refined unevenly, some levels deeper: its shared edge
    // carries m vertices of the lit square's leaves. Each of the edge's m + 1 segments needs an
    // element of its own (two points of the edge and one across), and m + 1 suffice: triangles to
    // the far corners and one quad. A fan from the centre would take m + 4.
    const BlackSquare b = black_square_beside_lit_one(with_lamp(settings(0.02f, 0.01), Vec3(1.1f, 0.3f, 0.1f)));
    ASSERT_GT(b.edge_vertices, 8u);
    EXPECT_EQ(b.elements, b.edge_vertices + 1);
}

TEST(Hierarchy, LeafBesideHundredsOfVerticesIsFannedFromItsCentre) {
    // As above with a lamp just over the shared edge: hundreds of vertices on it. The split's cost
    // grows as the cube of the vertices, so beyond 256 the black square is fanned from its centre
    // (m + 4 triangles), still without a T-vertex or a degenerate triangle.
    const BlackSquare b = black_square_beside_lit_one(with_lamp(settings(0.005f, 0.001), Vec3(1.02f, 0.5f, 0.02f)));
    ASSERT_GT(b.edge_vertices, 256u);
    EXPECT_EQ(b.elements, b.edge_vertices + 4);
}

/// n x n small patches on a floor (0.1 m apart) under an emitter 3 m up.
test::SceneArrays patch_grid(int n) {
    test::SceneArrays scene;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const float x = i * 0.1f, y = j * 0.1f;
            scene.add_quad({x, y, 0}, {x + 0.08f, y, 0}, {x + 0.08f, y + 0.08f, 0}, {x, y + 0.08f, 0}, Rgb(0.5));
        }
    const float c = n * 0.05f;
    scene.add_quad({c - 0.5f, c - 0.5f, 3}, {c - 0.5f, c + 0.5f, 3}, {c + 0.5f, c + 0.5f, 3}, {c + 0.5f, c - 0.5f, 3},
                   Rgb(0.0), Rgb(1.0));  // facing down
    return scene;
}

TEST(Hierarchy, ClustersKeepLinksNearLinear) {
    // Without clusters every pair of patches would need a link: n^2. With them, four times the
    // patches must take far less than sixteen times the links (n log n: about 4.8).
    const HierarchyResult small = bake_hierarchical(patch_grid(32).input(), settings(0.1f, 0.05));
    const HierarchyResult large = bake_hierarchical(patch_grid(64).input(), settings(0.1f, 0.05));
    EXPECT_GT(small.stats.clusters, 1000u);
    EXPECT_LT(double(large.stats.links) / double(small.stats.links), 6.0)
        << small.stats.links << " links for 1025 patches, " << large.stats.links << " for 4097";
    // Every patch is lit as the point formula says: L = rho E cos^2 A / (pi r^2).
    const auto means = polygon_means(small.output, small.output_radiance);
    const Vec3 light(1.6f, 1.6f, 3.0f);
    for (int p = 0; p < 1024; p += 37) {
        const Vec3 c(float(p / 32) * 0.1f + 0.04f, float(p % 32) * 0.1f + 0.04f, 0.0f);
        const Vec3 d = light - c;
        const float r2 = glm::dot(d, d), cosine = d.z / std::sqrt(r2);
        const double expected = 0.5 * cosine * cosine / (M_PI * r2);
        EXPECT_NEAR(means.at(p), expected, 0.05 * expected) << "patch " << p;
    }
}

TEST(Hierarchy, LeafCapStopsRefinementWithoutFailing) {
    const auto cornell = test::cornell_box();
    HierarchySettings s = settings(0.005f, 0.001);
    s.limits.max_elements = 2000;
    const HierarchyResult r = bake_hierarchical(cornell.input(), s);
    EXPECT_LE(r.stats.leaves, 2000u);
    EXPECT_TRUE(r.stats.leaf_cap_reached);
    for (const Rgb& L : r.output_radiance) EXPECT_TRUE(std::isfinite(L.r));
}

TEST(Hierarchy, MemoryCapStopsRefinementWithoutFailing) {
    // The Cornell box at 3 cm and refinement 0.01 takes about 100 MB of nodes and links; capped at
    // 4 MB, pairs stop splitting there and the bake still finishes with a finite answer.
    const auto cornell = test::cornell_box();
    HierarchySettings s = settings(0.03f, 0.01);
    s.max_bytes = std::size_t(4) << 20;
    const HierarchyResult r = bake_hierarchical(cornell.input(), s);
    EXPECT_TRUE(r.stats.memory_cap_reached);
    EXPECT_LE(r.stats.bytes, s.max_bytes + s.max_bytes / 100);  // splits under way when it was reached
    EXPECT_GT(r.stats.bytes, s.max_bytes / 2);
    for (const Rgb& L : r.output_radiance) EXPECT_TRUE(std::isfinite(L.r) && L.r >= 0.0);
    const auto means = polygon_means(r.output, r.output_radiance);
    EXPECT_GT(means.at(0), 0.0);  // the floor is lit
}

TEST(Hierarchy, CancelStopsTheBakeInEveryPhase) {
    const auto cornell = test::cornell_box();
    for (const std::string phase : {"elements", "links", "solve", "output"}) {
        std::size_t calls = 0;
        auto cancel_in_phase = [&](const Progress& p) {
            ++calls;
            return p.phase != phase;
        };
        EXPECT_THROW(bake_hierarchical(cornell.input(), settings(0.03f, 0.01), cancel_in_phase), Cancelled) << phase;
        EXPECT_GT(calls, 0u) << phase;
    }
}

/// The inside of a 2 m room, rho 0.7, one quad per side (polygon 0 the floor, 1 the ceiling, 2
/// to 5 the walls), a 50 cm square 1 cm under the ceiling emitting 10 (polygon 6; emitters are
/// two-sided, so it emits up into the gap too), reflecting 0.7 too: nothing is black and nothing
/// escapes, so every watt emitted is absorbed. `closed` false: the emitter is black (an Emission
/// shader's).
test::SceneArrays lit_room(bool closed = true) {
    test::SceneArrays s;
    const Rgb rho(0.7);
    const float z = 2.0f;
    s.add_quad({0, 0, 0}, {z, 0, 0}, {z, z, 0}, {0, z, 0}, rho);
    s.add_quad({0, 0, z}, {0, z, z}, {z, z, z}, {z, 0, z}, rho);
    s.add_quad({0, 0, 0}, {0, z, 0}, {0, z, z}, {0, 0, z}, rho);
    s.add_quad({z, 0, 0}, {z, 0, z}, {z, z, z}, {z, z, 0}, rho);
    s.add_quad({0, z, 0}, {z, z, 0}, {z, z, z}, {0, z, z}, rho);
    s.add_quad({0, 0, 0}, {0, 0, z}, {z, 0, z}, {z, 0, 0}, rho);
    const float lo = 0.75f, hi = 1.25f, lz = 1.99f;
    s.add_quad({lo, lo, lz}, {lo, hi, lz}, {hi, hi, lz}, {hi, lo, lz}, closed ? rho : Rgb(0.0), Rgb(10.0));
    return s;
}

/// A closed cube of side `size` standing on the floor at (x, y), six outward quads.
void add_block(test::SceneArrays& s, float x, float y, float size) {
    const Vec3 lo(x, y, 0.0f), hi(x + size, y + size, size);
    const Vec3 p[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                       {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
    const Rgb rho(0.7);
    s.add_quad(p[0], p[3], p[2], p[1], rho);  // bottom, on the floor
    s.add_quad(p[4], p[5], p[6], p[7], rho);
    s.add_quad(p[0], p[1], p[5], p[4], rho);
    s.add_quad(p[2], p[3], p[7], p[6], rho);
    s.add_quad(p[1], p[2], p[6], p[5], rho);
    s.add_quad(p[3], p[0], p[4], p[7], rho);
}

/// `count` blocks of 2 cm scattered on the floor as an artist's scatter leaves them: placed by a
/// fixed generator (some overlap), one in eight pressed against the one before (a shared face),
/// and one in sixteen beside the one before with its side 30 um from flush, so that the floor's
/// contact cuts leave slivers thinner than the weld tolerance between their outlines.
void scatter_blocks(test::SceneArrays& s, int count) {
    uint32_t seed = 12345u;
    auto uniform = [&] {
        seed = seed * 1664525u + 1013904223u;
        return float(seed >> 8) / 16777216.0f;
    };
    const float size = 0.02f;
    float x = 0.0f, y = 0.0f;
    for (int b = 0; b < count; ++b) {
        if (b % 8 == 1) {
            x += size;
        } else if (b % 16 == 2) {
            x += 3.0f * size;
            y += 3e-5f;
        } else {
            x = 0.05f + 1.9f * uniform();
            y = 0.05f + 1.9f * uniform();
        }
        add_block(s, x, y, size);
    }
}

/// Area-weighted mean radiance (mean of the channels) of the output elements on `polygons`.
double mean_radiance(const HierarchyResult& r, std::initializer_list<int32_t> polygons) {
    double power = 0.0, area = 0.0;
    for (std::size_t e = 0; e < r.output.size(); ++e)
        if (std::find(polygons.begin(), polygons.end(), r.output.polygon[e]) != polygons.end()) {
            power +=
                r.output.area[e] * (r.output_radiance[e].r + r.output_radiance[e].g + r.output_radiance[e].b) / 3.0;
            area += r.output.area[e];
        }
    return power / area;
}

/// Watts absorbed over watts emitted (energy.py's account): pi A (1 - rho) / rho (L - E) per
/// element against pi A E.
double absorbed_share(const HierarchyResult& r) {
    double absorbed = 0.0, emitted = 0.0;
    for (std::size_t e = 0; e < r.output.size(); ++e)
        for (int c = 0; c < 3; ++c) {
            const double rho = r.output.reflectance[e][c];
            emitted += r.output.area[e] * r.output.emission[e][c];
            if (rho > 0.0)
                absorbed += r.output.area[e] * (1.0 - rho) / rho * (r.output_radiance[e][c] - r.output.emission[e][c]);
        }
    return absorbed / emitted;
}

bool all_finite(const HierarchyResult& r) {
    auto finite = [](const Rgb& c) { return std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b); };
    return std::all_of(r.output_radiance.begin(), r.output_radiance.end(), finite) &&
           std::all_of(r.colors.element_corner.begin(), r.colors.element_corner.end(), finite) &&
           std::all_of(r.colors.input_corner.begin(), r.colors.input_corner.end(), finite);
}

TEST(Hierarchy, SliverThinnerThanTheWeldStaysWholeAndTheLightFinite) {
    // Pairs of blocks far apart on a lit room's floor, one 30 um off flush with the other: the
    // floor's contact cuts along their outlines (which keep lines 20 um apart: 1e-5 of the
    // floor's side) leave a strip 30 um wide between them, whose corners the tree's weld (35 um:
    // 1e-5 of the room's diagonal) makes two points. Split, it had children without area, whose area
    // mean was 0 / 0: NaN that every cluster above it turned into darkness (max(0, NaN) = 0), a
    // residual of NaN that read as 0, "converged" after two sweeps.
    test::SceneArrays room = lit_room(false);
    for (int pair = 0; pair < 4; ++pair) {
        const float y = 0.3f + 0.4f * pair, offset = 3e-5f * float(pair % 2 ? 1 : -1);
        add_block(room, 0.2f, y, 0.02f);
        add_block(room, 1.6f, y + offset, 0.02f);
    }
    HierarchySettings s = settings(0.05f, 0.02);
    s.tolerance = 1e-4;
    s.max_rounds = HierarchySettings().max_rounds;
    const HierarchyResult r = bake_hierarchical(room.input(), s);
    ASSERT_TRUE(all_finite(r));
    EXPECT_TRUE(std::isfinite(r.residual));
    EXPECT_GT(r.stats.iterations, 2);
    EXPECT_GT(r.stats.rounds, 1);
}

TEST(Hierarchy, ClutteredRoomKeepsTheEmptyRoomsLightAndAbsorbsWhatItEmits) {
    // Small blocks on a floor barely change a room's light (Cycles: 1,000 blocks of 2 cm leave the
    // walls 0.977x the empty room's). What this guards: a contact cut's sliver thinner than the
    // weld tolerance must not split into children without area (0 / 0: NaN); faces pressed
    // together must not light each other by round-off; clusters must not pass light between
    // parts that hide each other. Here 100 blocks (1% of the floor): the walls keep the empty room's light within 2%
    // (the blocks absorb about 1%), and the room, where nothing is black, absorbs what it emits within the hierarchy's
    // own error (the empty room absorbs 98.3% at this refinement).
    HierarchySettings s = settings(0.1f, 0.01);
    s.tolerance = 1e-4;
    s.max_rounds = HierarchySettings().max_rounds;
    const HierarchyResult empty = bake_hierarchical(lit_room().input(), s);
    test::SceneArrays cluttered = lit_room();
    scatter_blocks(cluttered, 100);
    const HierarchyResult r = bake_hierarchical(cluttered.input(), s);
    ASSERT_TRUE(all_finite(r));
    EXPECT_TRUE(r.converged);
    EXPECT_GT(r.stats.iterations, 2);
    const double walls = mean_radiance(r, {2, 3, 4, 5}) / mean_radiance(empty, {2, 3, 4, 5});
    const double floor = mean_radiance(r, {0}) / mean_radiance(empty, {0});
    std::printf("walls %.4f x, floor %.4f x the empty room's; absorbed %.4f (empty room %.4f) of the emitted\n", walls,
                floor, absorbed_share(r), absorbed_share(empty));
    EXPECT_NEAR(walls, 1.0, 0.02);
    EXPECT_NEAR(floor, 1.0, 0.03);
    EXPECT_NEAR(absorbed_share(empty), 1.0, 0.02);
    EXPECT_NEAR(absorbed_share(r), 1.0, 0.02);
    EXPECT_LT(absorbed_share(r), 1.001);  // no light made from nothing
}

TEST(Hierarchy, SameSceneBakesBitIdentically) {
    // Threads split nodes and make links in an order of their own; the nodes are numbered and each
    // node's links summed as one thread would, so nothing the bake computes depends on that order.
    // A room with blocks, an emitter and a point lamp (lamp detail splits leaves after the solve).
    test::SceneArrays room = lit_room();
    scatter_blocks(room, 20);
    HierarchySettings s = with_lamp(settings(0.1f, 0.02), Vec3(1.0f, 0.7f, 1.5f));
    s.tolerance = 1e-4;
    s.max_rounds = HierarchySettings().max_rounds;
    const HierarchyResult first = bake_hierarchical(room.input(), s);
    for (int run = 0; run < 3; ++run) {
        const HierarchyResult again = bake_hierarchical(room.input(), s);
        ASSERT_EQ(again.output.size(), first.output.size());
        EXPECT_EQ(again.stats.links, first.stats.links);
        EXPECT_TRUE(again.output_radiance == first.output_radiance) << run;
        EXPECT_TRUE(again.colors.element_corner == first.colors.element_corner) << run;
        EXPECT_TRUE(again.colors.input_corner == first.colors.input_corner) << run;
    }
}

TEST(Hierarchy, SceneOfDegeneratePolygonsBakesToNothing) {
    // Every polygon skipped (NaN, zero area), a lamp still there: no elements, no crash.
    test::SceneArrays scene;
    scene.add_polygon({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, Rgb(0.5), Rgb(0.0));
    scene.add_polygon({{0, 0, 0}, {1, 0, 0}, {1, 1, std::nanf("")}}, Rgb(0.5), Rgb(1.0));
    const HierarchyResult r = bake_hierarchical(scene.input(), with_lamp(settings(0.1f, 0.01), Vec3(0, 0, 1)));
    EXPECT_EQ(r.output.size(), 0u);
    EXPECT_EQ(r.build.skipped.size(), 2u);
    for (const Rgb& c : r.colors.input_corner) EXPECT_EQ(c, Rgb(0.0));
}

TEST(Hierarchy, BadSettingsAreInputErrors) {
    const auto box = test::closed_box(Vec3(1), Rgb(0.5), Rgb(1.0));
    EXPECT_THROW(bake_hierarchical(box.input(), settings(0.0f, 0.01)), InputError);
    EXPECT_THROW(bake_hierarchical(box.input(), settings(0.1f, std::nan(""))), InputError);
    HierarchySettings detail = settings(0.1f, 0.01);
    detail.lamp_detail_levels = -1;
    EXPECT_THROW(bake_hierarchical(box.input(), detail), InputError);
}

/// A rectangle from `a` along `u` and `v` (its normal u x v), as tiles of at most `tile` metres.
void add_tiled(test::SceneArrays& s, const Vec3& a, const Vec3& u, const Vec3& v, float tile, const Rgb& rho) {
    const int nu = int(std::ceil(glm::length(u) / tile)), nv = int(std::ceil(glm::length(v) / tile));
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            const Vec3 p = a + u * (float(i) / nu) + v * (float(j) / nv), du = u / float(nu), dv = v / float(nv);
            s.add_quad(p, p + du, p + du + dv, p + dv, rho);
        }
}

/// A closed box [lo, hi] seen from inside, its sides in tiles of 1 m (as a level's brushes cut them).
void add_tiled_room(test::SceneArrays& s, const Vec3& lo, const Vec3& hi, const Rgb& rho) {
    const Vec3 d = hi - lo, X(d.x, 0, 0), Y(0, d.y, 0), Z(0, 0, d.z);
    add_tiled(s, lo, X, Y, 1.0f, rho);
    add_tiled(s, lo + Z, Y, X, 1.0f, rho);
    add_tiled(s, lo, Z, X, 1.0f, rho);
    add_tiled(s, lo + Y, X, Z, 1.0f, rho);
    add_tiled(s, lo, Y, Z, 1.0f, rho);
    add_tiled(s, lo + X, Z, Y, 1.0f, rho);
}

/// Area-weighted mean radiance (red) of the output elements whose centres lie between x0 and x1.
double mean_between(const HierarchyResult& r, float x0, float x1) {
    double power = 0.0, area = 0.0;
    for (std::size_t e = 0; e < r.output.size(); ++e)
        if (r.output.centre[e].x > x0 && r.output.centre[e].x < x1) {
            power += r.output.area[e] * r.output_radiance[e].r;
            area += r.output.area[e];
        }
    return power / area;
}

TEST(Hierarchy, ClosedRoomsBesideALitOneStayBlack) {
    // Three closed 4 x 3 x 2.5 m rooms in a row, 2 cm or 20 cm walls between them (each room's own
    // wall, back to back), a lamp in the first: no light reaches the other two, exactly. Light that
    // links between clusters carried through a wall (the classic leak of clustering, rays that skip
    // what lies inside the clusters' bounding spheres) would show there.
    for (const float wall : {0.02f, 0.2f}) {
        test::SceneArrays rooms;
        for (int k = 0; k < 3; ++k)
            add_tiled_room(rooms, {k * (4 + wall), 0, 0}, {k * (4 + wall) + 4, 3, 2.5f}, Rgb(0.7));
        HierarchySettings s = with_lamp(settings(0.25f, 0.02), Vec3(2.0f, 1.5f, 1.5f));
        s.tolerance = 1e-4;
        s.max_rounds = HierarchySettings().max_rounds;
        const HierarchyResult r = bake_hierarchical(rooms.input(), s);
        EXPECT_GT(mean_between(r, -1.0f, 4.0f), 0.1) << wall;
        EXPECT_EQ(mean_between(r, 4.0f + wall, 8.0f + wall), 0.0) << wall;
        EXPECT_EQ(mean_between(r, 8.0f + 2 * wall, 13.0f), 0.0) << wall;
    }
}

}  // namespace
}  // namespace radiosity
