/// @file test_interpolation.cpp
/// @brief Corner colours against the classic 2x2 example of border extrapolation, linear fields, hard edges, materials,
/// clamping.
#include "output/interpolation.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <functional>
#include <map>

namespace radiosity {
namespace {

using Field = std::function<Rgb(const Vec3&)>;

/// Elements built by hand, grid by grid, each grid one polygon with its own vertices;
/// radiance[e] = field(centre of e).
struct Builder {
    Elements el;
    std::vector<Rgb> radiance;
    int32_t polygons = 0;

    /// An nx x ny grid of quads (or of triangles, each quad cut along a diagonal) spanning
    /// origin + [0,nx] u + [0,ny] v, normal along u x v. Adds the grid's 4 corners as input corners.
    int32_t add_grid(Vec3 origin, Vec3 u, Vec3 v, int nx, int ny, const Field& field, bool triangles = false) {
        const int32_t polygon = polygons++;
        const auto first = static_cast<int32_t>(el.vertices.size());
        for (int j = 0; j <= ny; ++j)
            for (int i = 0; i <= nx; ++i) el.vertices.push_back(origin + float(i) * u + float(j) * v);
        auto id = [&](int i, int j) { return first + j * (nx + 1) + i; };
        const Vec3 normal = glm::normalize(glm::cross(u, v));
        auto add = [&](std::array<int32_t, 4> c) {
            const int m = c[3] < 0 ? 3 : 4;
            Vec3 centre(0.0f);
            for (int k = 0; k < m; ++k) centre += el.vertices[c[k]] / float(m);
            el.corners.push_back(c);
            el.centre.push_back(centre);
            el.normal.push_back(normal);
            el.area.push_back(glm::length(glm::cross(u, v)) / (m == 3 ? 2.0f : 1.0f));
            el.polygon.push_back(polygon);
            el.reflectance.push_back(Rgb(0.5));
            el.emission.push_back(Rgb(0.0));
            radiance.push_back(field(centre));
        };
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                if (triangles) {
                    add({id(i, j), id(i + 1, j), id(i + 1, j + 1), -1});
                    add({id(i, j), id(i + 1, j + 1), id(i, j + 1), -1});
                } else {
                    add({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
                }
            }
        for (const int32_t c : {id(0, 0), id(nx, 0), id(nx, ny), id(0, ny)}) el.corner_vertex.push_back(c);
        return polygon;
    }

    Vec3 corner_position(std::size_t e, int k) const { return el.vertices[el.corners[e][k]]; }
};

Field constant(Rgb c) {
    return [c](const Vec3&) { return c; };
}

Rgb linear(const Vec3& p) {  // positive over the test grids, different per channel
    return Rgb(1.0 + 0.3 * p.x + 0.7 * p.y, 2.0 - 0.2 * p.x + 0.1 * p.y, 0.5 + 0.05 * p.x + 0.02 * p.y + 0.1 * p.z);
}

void expect_near(const Rgb& a, const Rgb& b, double tolerance, const std::string& where) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], tolerance) << where << " channel " << c;
}

TEST(Interpolation, SeedTwoByTwoExample) {
    // Four elements, F1 F2 over F3 F4, vertices a b c / d e f / g h i.
    const Rgb B1(10, 1, 4), B2(12, 2, 4), B3(11, 1, 5), B4(15, 3, 6);
    const Vec3 a(0, 2, 0), b(1, 2, 0), c(2, 2, 0), d(0, 1, 0), e(1, 1, 0), f(2, 1, 0), g(0, 0, 0), h(1, 0, 0),
        i(2, 0, 0);
    const Field field = [&](const Vec3& p) { return p.y > 1 ? (p.x < 1 ? B1 : B2) : (p.x < 1 ? B3 : B4); };
    const Rgb Be = (B1 + B2 + B3 + B4) / 4.0;
    const Rgb Ba = B1 + (B1 - Be), Bc = B2 + (B2 - Be), Bg = B3 + (B3 - Be), Bi = B4 + (B4 - Be);
    const std::map<std::array<float, 2>, Rgb> expected = {
        {{a.x, a.y}, Ba}, {{b.x, b.y}, (Ba + Bc) / 2.0}, {{c.x, c.y}, Bc}, {{d.x, d.y}, (Ba + Bg) / 2.0},
        {{e.x, e.y}, Be}, {{f.x, f.y}, (Bc + Bi) / 2.0}, {{g.x, g.y}, Bg}, {{h.x, h.y}, (Bg + Bi) / 2.0},
        {{i.x, i.y}, Bi}};

    // One polygon of four elements, and four polygons welded by position: the same answer.
    Builder one, four;
    one.add_grid(g, Vec3(1, 0, 0), Vec3(0, 1, 0), 2, 2, field);
    for (const Vec3 origin : {g, h, d, e}) four.add_grid(origin, Vec3(1, 0, 0), Vec3(0, 1, 0), 1, 1, field);
    for (const Builder* s : {&one, &four}) {
        const CornerColors colors = interpolate_corners(s->el, s->radiance, nullptr, 0.5236f);
        ASSERT_EQ(colors.element_corner.size(), 16u);
        for (std::size_t el = 0; el < 4; ++el)
            for (int k = 0; k < 4; ++k) {
                const Vec3 p = s->corner_position(el, k);
                expect_near(colors.element_corner[4 * el + k], expected.at({p.x, p.y}), 1e-12,
                            "element " + std::to_string(el) + " corner " + std::to_string(k));
            }
    }
}

TEST(Interpolation, LinearFieldIsReproducedEverywhere) {
    for (bool triangles : {false, true}) {
        Builder s;
        s.add_grid(Vec3(0.2f, -0.5f, 0.0f), Vec3(0.5f, 0, 0), Vec3(0, 0.25f, 0), 5, 4, linear, triangles);
        const CornerColors colors = interpolate_corners(s.el, s.radiance, nullptr, 0.5236f);
        for (std::size_t e = 0; e < s.el.size(); ++e)
            for (int k = 0; k < (s.el.is_triangle(e) ? 3 : 4); ++k)
                expect_near(colors.element_corner[4 * e + k], linear(s.corner_position(e, k)), 1e-6,
                            std::string(triangles ? "triangles" : "quads") + " element " + std::to_string(e));
    }
}

TEST(Interpolation, LinearFieldAcrossWeldedPolygons) {
    // A 4 x 4 grid as four 2 x 2 polygons with their own vertices: seams are interior.
    Builder s;
    const Vec3 u(0.5f, 0, 0), v(0, 0.5f, 0);
    for (const Vec3 origin : {Vec3(0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)})
        s.add_grid(origin, u, v, 2, 2, linear);
    const CornerColors colors = interpolate_corners(s.el, s.radiance, nullptr, 0.5236f);
    for (std::size_t e = 0; e < s.el.size(); ++e)
        for (int k = 0; k < 4; ++k)
            expect_near(colors.element_corner[4 * e + k], linear(s.corner_position(e, k)), 1e-6,
                        "element " + std::to_string(e));
    // The input corners are the polygon corners' values.
    ASSERT_EQ(colors.input_corner.size(), 16u);
    for (std::size_t c = 0; c < 16; ++c)
        expect_near(colors.input_corner[c], linear(s.el.vertices[s.el.corner_vertex[c]]), 1e-6, "input corner");
}

TEST(Interpolation, WeldsWithinToleranceOnly) {
    // Two unit quads side by side (radiance 1 and 3), the second's vertices moved by `shift`:
    // 1e-5 m is within the weld tolerance (1e-5 of the 2.2 m diagonal) and blends the seam;
    // 1e-3 m leaves a gap, so each quad keeps its own value.
    for (const float shift : {1e-5f, 1e-3f}) {
        Builder s;
        s.add_grid(Vec3(0), Vec3(1, 0, 0), Vec3(0, 1, 0), 1, 1, constant(Rgb(1.0)));
        s.add_grid(Vec3(1.0f + shift, shift, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), 1, 1, constant(Rgb(3.0)));
        const CornerColors colors = interpolate_corners(s.el, s.radiance, nullptr, 0.5236f);
        // Element 0's corner 1 (1,0,0) meets element 1's corner 0 at the seam.
        if (shift < 1e-4f) {
            expect_near(colors.element_corner[1], Rgb(2.0), 1e-4, "welded seam, left");
            expect_near(colors.element_corner[4], Rgb(2.0), 1e-4, "welded seam, right");
        } else {
            EXPECT_EQ(colors.element_corner[1], Rgb(1.0));
            EXPECT_EQ(colors.element_corner[4], Rgb(3.0));
        }
    }
}

TEST(Interpolation, HardEdgesDoNotBlend) {
    // Three faces of a box corner at the origin, each uniform: a 90 degree fold is a hard edge at
    // 30 degrees, so every face keeps its own value; at 100 degrees they blend.
    Builder s;
    s.add_grid(Vec3(0), Vec3(0.5f, 0, 0), Vec3(0, 0.5f, 0), 2, 2, constant(Rgb(1.0)));  // z = 0
    s.add_grid(Vec3(0), Vec3(0, 0.5f, 0), Vec3(0, 0, 0.5f), 2, 2, constant(Rgb(5.0)));  // x = 0
    s.add_grid(Vec3(0), Vec3(0, 0, 0.5f), Vec3(0.5f, 0, 0), 2, 2, constant(Rgb(9.0)));  // y = 0
    const CornerColors hard = interpolate_corners(s.el, s.radiance, nullptr, 0.5236f);
    for (std::size_t e = 0; e < s.el.size(); ++e)
        for (int k = 0; k < 4; ++k) expect_near(hard.element_corner[4 * e + k], s.radiance[e], 1e-12, "hard");
    const CornerColors soft = interpolate_corners(s.el, s.radiance, nullptr, 1.75f);
    EXPECT_NE(soft.element_corner[0], hard.element_corner[0]);  // element 0's corner 0 is the box corner
}

TEST(Interpolation, MaterialsDoNotBlend) {
    Builder s;
    s.add_grid(Vec3(0), Vec3(0.5f, 0, 0), Vec3(0, 0.5f, 0), 2, 2, constant(Rgb(1.0)));
    s.add_grid(Vec3(1, 0, 0), Vec3(0.5f, 0, 0), Vec3(0, 0.5f, 0), 2, 2, constant(Rgb(3.0)));
    const std::vector<int32_t> different = {0, 1}, same = {4, 4};
    const CornerColors apart = interpolate_corners(s.el, s.radiance, different.data(), 0.5236f);
    for (std::size_t e = 0; e < s.el.size(); ++e)
        for (int k = 0; k < 4; ++k) expect_near(apart.element_corner[4 * e + k], s.radiance[e], 1e-12, "apart");
    const CornerColors together = interpolate_corners(s.el, s.radiance, same.data(), 0.5236f);
    const CornerColors no_material = interpolate_corners(s.el, s.radiance, nullptr, 0.5236f);
    EXPECT_EQ(together.element_corner, no_material.element_corner);
    // Element 1 (x in [0.5, 1]) touches the seam at its corner 1: blended there.
    EXPECT_GT(together.element_corner[4 * 1 + 1].r, 1.5);
}

TEST(Interpolation, ExtrapolationIsClampedAtZero) {
    Builder s;
    const Field field = [](const Vec3& p) { return p.x < 1 && p.y > 1 ? Rgb(0.0, 5.0, 0.0) : Rgb(4.0, 5.0, 0.0); };
    s.add_grid(Vec3(0), Vec3(1, 0, 0), Vec3(0, 1, 0), 2, 2, field);
    const CornerColors colors = interpolate_corners(s.el, s.radiance, nullptr, 0.5236f);
    // Element 2 is the top-left (radiance 0 in red); its corner 3 is the example's a: 0 + (0 - 3) < 0.
    ASSERT_EQ(s.radiance[2].r, 0.0);
    EXPECT_EQ(colors.element_corner[4 * 2 + 3], Rgb(0.0, 5.0, 0.0));
    for (const Rgb& c : colors.element_corner) EXPECT_GE(glm::min(c.r, glm::min(c.g, c.b)), 0.0);
}

TEST(Interpolation, InputCornersOfSubdividedQuadAndSkippedPolygons) {
    Builder s;
    s.add_grid(Vec3(0.1f, 0.2f, 0.3f), Vec3(0.3f, 0, 0.1f), Vec3(0, 0.3f, 0), 3, 3, linear);
    s.el.corner_vertex.insert(s.el.corner_vertex.end(), {-1, -1, -1});  // a skipped triangle
    const CornerColors colors = interpolate_corners(s.el, s.radiance, nullptr, 0.5236f);
    ASSERT_EQ(colors.input_corner.size(), 7u);
    for (std::size_t c = 0; c < 4; ++c) {
        const int32_t v = s.el.corner_vertex[c];
        expect_near(colors.input_corner[c], linear(s.el.vertices[v]), 1e-6, "corner " + std::to_string(c));
        for (std::size_t e = 0; e < s.el.size(); ++e)
            for (int k = 0; k < 4; ++k)
                if (s.el.corners[e][k] == v) EXPECT_EQ(colors.input_corner[c], colors.element_corner[4 * e + k]);
    }
    for (std::size_t c = 4; c < 7; ++c) EXPECT_EQ(colors.input_corner[c], Rgb(0.0));
}

}  // namespace
}  // namespace radiosity
