/// @file test_stability_contacts.cpp
/// @brief Contact lines: a box standing on a floor leaks light under it, and its dark footprint
/// smears into the lit floor, unless the floor is cut along the box's outline
/// (ElementLimits::cut_contacts, on in the uniform bake).

#include "bake/bake.h"
#include "hierarchy/hierarchy.h"
#include "testing/test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace radiosity;

namespace {

constexpr double kRho = 0.5, kSun = 1.0;   // floor reflectance, sun irradiance
constexpr float kLo = 0.13f, kHi = 0.53f;  // the box's footprint [kLo, kHi]^2, 0.4 m tall
const double kLit = kRho * kSun / M_PI;    // the lit floor's exact radiance

/// A 2 x 2 m floor with a black 0.4 m box standing on it (bottom face included, facing down), lit
/// by a sun straight down: the floor is exactly kLit outside the footprint and 0 inside it (the
/// box casts no other shadow and reflects nothing).
test::SceneArrays box_on_floor() {
    test::SceneArrays s;
    s.add_quad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, Rgb(kRho));
    const float a = kLo, b = kHi, h = 0.4f;
    s.add_quad({a, a, 0}, {a, b, 0}, {b, b, 0}, {b, a, 0}, Rgb(0));  // bottom, facing down
    s.add_quad({a, a, h}, {b, a, h}, {b, b, h}, {a, b, h}, Rgb(0));  // top
    s.add_quad({a, a, 0}, {b, a, 0}, {b, a, h}, {a, a, h}, Rgb(0));  // -y
    s.add_quad({b, a, 0}, {b, b, 0}, {b, b, h}, {b, a, h}, Rgb(0));  // +x
    s.add_quad({b, b, 0}, {a, b, 0}, {a, b, h}, {b, b, h}, Rgb(0));  // +y
    s.add_quad({a, b, 0}, {a, a, 0}, {a, a, h}, {a, b, h}, Rgb(0));  // -x
    return s;
}

struct ContactMeasure {
    int straddling = 0;      ///< floor elements with corners inside and outside the footprint
    double lit_ring = 0.0;   ///< worst |L - lit| / lit of floor elements reaching outside and touching the outline
    double footprint = 0.0;  ///< brightest floor element reaching into the footprint / lit (light under the box)
    double lit_corner =
        0.0;  ///< worst |colour - lit| / lit at corners outside or on the outline of elements reaching outside
    double dark_corner =
        0.0;  ///< brightest colour / lit at corners inside or on the outline of elements reaching inside
};

bool inside(const Vec3& v, float slack) {
    return v.x > kLo + slack && v.x < kHi - slack && v.y > kLo + slack && v.y < kHi - slack;
}
bool outside(const Vec3& v, float slack) {
    return v.x < kLo - slack || v.x > kHi + slack || v.y < kLo - slack || v.y > kHi + slack;
}

/// The floor's elements (polygon 0) of a bake of box_on_floor: its mesh, radiances and corner colours.
ContactMeasure measure_floor(const Elements& e, const std::vector<Rgb>& radiance, const std::vector<Rgb>& corners) {
    ContactMeasure m;
    const float slack = 1e-5f;
    for (std::size_t i = 0; i < e.size(); ++i) {
        if (e.polygon[i] != 0) continue;
        const int n = e.is_triangle(i) ? 3 : 4;
        bool any_in = false, any_out = false, touches = false;
        for (int k = 0; k < n; ++k) {
            const Vec3& v = e.vertices[e.corners[i][k]];
            any_in = any_in || inside(v, slack);
            any_out = any_out || outside(v, slack);
            touches = touches || !outside(v, slack);
        }
        const double L = radiance[i].g;
        m.straddling += any_in && any_out;
        if (any_in) m.footprint = std::max(m.footprint, L / kLit);
        if (any_out && touches) m.lit_ring = std::max(m.lit_ring, std::abs(L - kLit) / kLit);
        for (int k = 0; k < n; ++k) {
            const Vec3& v = e.vertices[e.corners[i][k]];
            const double colour = corners[4 * i + k].g;
            if (any_in && !outside(v, slack)) m.dark_corner = std::max(m.dark_corner, colour / kLit);
            if (any_out && !inside(v, slack)) m.lit_corner = std::max(m.lit_corner, std::abs(colour - kLit) / kLit);
        }
    }
    return m;
}

void print(const char* bake, float element_size, bool cut, const ContactMeasure& m) {
    std::printf(
        "box on floor, %s, %.2f m elements, cut %s: %d straddling; lit ring error %.4f, footprint %.4f of the "
        "lit floor; corners on the outline: lit side error %.4f, dark side %.4f\n",
        bake, element_size, cut ? "on " : "off", m.straddling, m.lit_ring, m.footprint, m.lit_corner, m.dark_corner);
}

ContactMeasure measure(float element_size, bool cut) {
    BakeSettings s;
    s.element_size = element_size;
    s.resolution = 64;
    s.limits.cut_intersections = cut;
    s.lights.suns.push_back({Vec3(0, 0, -1), Rgb(kSun)});
    const BakeResult r = bake(box_on_floor().input(), s);
    const ContactMeasure m = measure_floor(r.build.elements, r.solve.radiance, r.colors.element_corner);
    print("uniform", element_size, cut, m);
    return m;
}

/// The hierarchical bake (contacts always cut) down to `min_element_size`.
ContactMeasure measure_hierarchical(float min_element_size) {
    HierarchySettings s;
    s.min_element_size = min_element_size;
    s.lights.suns.push_back({Vec3(0, 0, -1), Rgb(kSun)});
    const HierarchyResult r = bake_hierarchical(box_on_floor().input(), s);
    const ContactMeasure m = measure_floor(r.output, r.output_radiance, r.colors.element_corner);
    print("hierarchical", min_element_size, true, m);
    return m;
}

}  // namespace

TEST(Contacts, UncutFloorLeaksUnderABoxAndDarkensAroundIt) {
    for (float size : {0.3f, 0.12f}) {  // 8 and 16 floor elements straddle the outline
        const ContactMeasure m = measure(size, false);
        EXPECT_GT(m.straddling, 0);
        EXPECT_GT(m.footprint, 0.9);    // measured 0.998 and 1.0: the lit floor reaches under the box
        EXPECT_GT(m.lit_ring, 0.3);     // measured 0.35 and 0.38: the floor around it is darkened
        EXPECT_GT(m.dark_corner, 0.7);  // measured 0.73 and 0.75
        EXPECT_GT(m.lit_corner, 0.1);   // measured 0.12 and 0.19
    }
}

TEST(Contacts, CutAlongTheOutlineKeepsTheFootprintDarkAndTheFloorLit) {
    for (float size : {0.3f, 0.12f}) {
        const ContactMeasure m = measure(size, true);
        EXPECT_EQ(m.straddling, 0);
        // The truth is exact (0 under the box, rho E / pi around it): only float round-off may remain
        // (measured 0).
        EXPECT_LT(m.footprint, 1e-5);
        EXPECT_LT(m.lit_ring, 1e-5);
        // Corner colours are not blended across the outline: each side is extrapolated from its own.
        EXPECT_LT(m.dark_corner, 1e-5);
        EXPECT_LT(m.lit_corner, 1e-5);
    }
}

TEST(Contacts, HierarchyKeepsTheFootprintDarkAndTheFloorLit) {
    // Its leaves keep their patch's cut edges, so interpolation does not blend the lit floor with
    // the footprint (before: corners on the lit side 0.27 off).
    for (float size : {0.3f, 0.12f}) {
        const ContactMeasure m = measure_hierarchical(size);
        EXPECT_EQ(m.straddling, 0);
        EXPECT_LT(m.footprint, 1e-5);
        EXPECT_LT(m.lit_ring, 1e-5);
        EXPECT_LT(m.dark_corner, 1e-5);
        EXPECT_LT(m.lit_corner, 1e-5);
    }
}

TEST(Contacts, CornellBoxIsCutAlongTheBlocksAndTheLightOnly) {
    // The floor along the blocks standing on it; the ceiling along the light hung 1 mm under it,
    // whose back side lights it up to that outline (emitting faces are two-sided).
    const Elements e = build_elements(test::cornell_box().input(), 0.1f, ElementLimits().with_contacts()).elements;
    int flagged[2] = {0, 0};
    for (std::size_t i = 0; i < e.size(); ++i)
        for (int k = 0; k < 4; ++k) {
            if (!((e.cut_edges[i] >> k) & 1)) continue;
            ASSERT_TRUE(e.polygon[i] == 0 || e.polygon[i] == 1) << "only the floor and the ceiling are cut";
            ++flagged[e.polygon[i]];
            const Vec3 &a = e.vertices[e.corners[i][k]], &b = e.vertices[e.corners[i][(k + 1) % 4]];
            // On a block's outline: x or y constant at one of its sides, 0.15/0.45 or 0.55/0.85.
            // On the light's: 0.4/0.6.
            auto side = [&](float v) {
                return e.polygon[i] == 0 ? v == 0.15f || v == 0.45f || v == 0.55f || v == 0.85f
                                         : v == 0.4f || v == 0.6f;
            };
            const bool on_side = (a.x == b.x && side(a.x)) || (a.y == b.y && side(a.y));
            EXPECT_TRUE(on_side) << e.polygon[i] << ": " << a.x << " " << a.y << " - " << b.x << " " << b.y;
        }
    EXPECT_GT(flagged[0], 0);
    EXPECT_GT(flagged[1], 0);
}

TEST(Contacts, WallsMeetingAtEdgesAreNotCut) {
    // A closed room: every wall stands on the floor's edge, where no floor is on the other side.
    const auto room = test::closed_box(Vec3(1, 2, 1.5f), Rgb(0.5), Rgb(0.1));
    const Elements e = build_elements(room.input(), 0.25f, ElementLimits().with_contacts()).elements;
    for (const uint8_t bits : e.cut_edges) EXPECT_EQ(bits, 0);
    EXPECT_EQ(test::front_count(e), 2u * (4 * 8 + 4 * 6 + 8 * 6));
}

TEST(Contacts, AFaceOnAConcaveNeighboursEdgeIsNoCut) {
    // An L-shaped floor and a wall standing on its inner edge x = 1, y in [1, 2]: the wall's plane
    // passes through the floor (corners at x = 0 and 2), but the contact is the floor's own outline.
    test::SceneArrays scene;
    scene.add_polygon({{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}}, Rgb(0.5), Rgb(0));
    scene.add_quad({1, 1, 0}, {1, 1, 1}, {1, 2, 1}, {1, 2, 0}, Rgb(0.5));
    const Elements e = build_elements(scene.input(), 0.3f, ElementLimits().with_contacts()).elements;
    for (const uint8_t bits : e.cut_edges) EXPECT_EQ(bits, 0);
    // The same wall standing inside the floor, at x = 0.5, cuts it.
    test::SceneArrays inside_floor;
    inside_floor.add_polygon({{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}}, Rgb(0.5), Rgb(0));
    inside_floor.add_quad({0.5f, 1, 0}, {0.5f, 1, 1}, {0.5f, 2, 1}, {0.5f, 2, 0}, Rgb(0.5));
    int flagged = 0;
    for (const uint8_t bits :
         build_elements(inside_floor.input(), 0.3f, ElementLimits().with_contacts()).elements.cut_edges)
        flagged += __builtin_popcount(bits);
    EXPECT_GT(flagged, 0);
}
