/// @file test_textures.cpp
/// @brief Image textures in the bake (texture.h): Cycles' texel lookup, each element's colour as the
/// texture's mean over its footprint (against integrals done by hand), an emitting texture's
/// flux, and output corners that show the texel there times the light arriving.
#include "bake/bake.h"
#include "geometry/texture.h"

#include "testing/test_util.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace radiosity {
namespace {

/// A texture that owns its texels (row 0 at v = 0).
struct OwnedTexture {
    std::vector<float> rgb;
    Texture view;
    OwnedTexture(int width, int height, TextureFilter filter, TextureExtension extension) : rgb(3 * width * height) {
        view.width = width;
        view.height = height;
        view.filter = filter;
        view.extension = extension;
    }
    void set(int x, int y, double grey) {
        for (int c = 0; c < 3; ++c) rgb[3 * (y * view.width + x) + c] = float(grey);
        view.rgb = rgb.data();
    }
};

/// An n x n checker of `a` and `b` (a at texel (0, 0)).
OwnedTexture checker(int n, double a, double b, TextureFilter filter) {
    OwnedTexture t(n, n, filter, TextureExtension::Repeat);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) t.set(x, y, (x + y) % 2 ? b : a);
    return t;
}

/// `width` texels along u, texel i holding (i + 0.5) / width: with Linear and Extend, the value at
/// u is u itself, clamped to the first and last texel centres.
OwnedTexture ramp(int width) {
    OwnedTexture t(width, 1, TextureFilter::Linear, TextureExtension::Extend);
    for (int x = 0; x < width; ++x) t.set(x, 0, (x + 0.5) / width);
    return t;
}

/// The integral of clamp(u, lo, hi) over [a, b].
double clamped_integral(double a, double b, double lo, double hi) {
    auto primitive = [&](double u) {  // of clamp(s, lo, hi) from 0 to u, for u >= 0
        if (u <= lo) return lo * u;
        if (u <= hi) return lo * lo + (u * u - lo * lo) / 2.0;
        return lo * lo + (hi * hi - lo * lo) / 2.0 + hi * (u - hi);
    };
    return primitive(b) - primitive(a);
}

/// The mean of the n x n checker (squares 1/n wide in UV) over the UV rectangle [x0, x1] x [y0, y1]:
/// each square's value times the area it shares with the rectangle.
double checker_mean(int n, double a, double b, double x0, double x1, double y0, double y1) {
    double sum = 0.0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const double w = std::max(0.0, std::min(x1, (i + 1.0) / n) - std::max(x0, double(i) / n));
            const double h = std::max(0.0, std::min(y1, (j + 1.0) / n) - std::max(y0, double(j) / n));
            sum += w * h * ((i + j) % 2 ? b : a);
        }
    return sum / ((x1 - x0) * (y1 - y0));
}

/// Polygons of `s` with UVs, each face textured by texture 0 in one role (scale 1).
struct Textured {
    std::vector<float> uv;
    std::vector<int32_t> index;
    std::vector<float> scale;
    SurfaceTextures textures;

    Textured(const test::SceneArrays& s, const Texture& t, bool emission) {
        for (const int32_t v : s.corner_vertices) {  // UV = the corner's (x, y)
            uv.push_back(s.positions[3 * v]);
            uv.push_back(s.positions[3 * v + 1]);
        }
        index.assign(s.material.size(), 0);
        scale.assign(3 * s.material.size(), 1.0f);
        textures.textures = {t};
        textures.corner_uv = uv.data();
        (emission ? textures.emission_texture : textures.reflectance_texture) = index.data();
        (emission ? textures.emission_scale : textures.reflectance_scale) = scale.data();
    }
};

/// The element's extent in x and y.
void element_box(const Elements& e, std::size_t k, double& x0, double& x1, double& y0, double& y1) {
    x0 = y0 = 1e9;
    x1 = y1 = -1e9;
    for (int c = 0; c < e.corner_count(k); ++c) {
        const Vec3 p = e.vertices[e.corners[k][c]];
        x0 = std::min(x0, double(p.x)), x1 = std::max(x1, double(p.x));
        y0 = std::min(y0, double(p.y)), y1 = std::max(y1, double(p.y));
    }
}

TEST(Texture, LookupIsCyclesLinearAndClosest) {
    OwnedTexture t(2, 1, TextureFilter::Linear, TextureExtension::Repeat);
    t.set(0, 0, 0.0);
    t.set(1, 0, 1.0);
    // Texel centres at u = 0.25 and 0.75; between them the blend, beyond them the extension.
    EXPECT_DOUBLE_EQ(texel(t.view, 0.25f, 0.5f).r, 0.0);
    EXPECT_DOUBLE_EQ(texel(t.view, 0.5f, 0.5f).r, 0.5);
    EXPECT_DOUBLE_EQ(texel(t.view, 0.625f, 0.5f).r, 0.75);
    EXPECT_DOUBLE_EQ(texel(t.view, 0.0f, 0.5f).r, 0.5);  // repeat: blends the last texel and the first
    t.view.extension = TextureExtension::Extend;
    EXPECT_DOUBLE_EQ(texel(t.view, 0.0f, 0.5f).r, 0.0);
    EXPECT_DOUBLE_EQ(texel(t.view, 1.0f, 0.5f).r, 1.0);
    t.view.extension = TextureExtension::Clip;  // black beyond the edge texels
    EXPECT_DOUBLE_EQ(texel(t.view, 1.0f, 0.5f).r, 0.5);
    EXPECT_DOUBLE_EQ(texel(t.view, 1.5f, 0.5f).r, 0.0);
    t.view.filter = TextureFilter::Closest;
    t.view.extension = TextureExtension::Repeat;
    EXPECT_DOUBLE_EQ(texel(t.view, 0.49f, 0.5f).r, 0.0);
    EXPECT_DOUBLE_EQ(texel(t.view, 0.51f, 0.5f).r, 1.0);
    EXPECT_DOUBLE_EQ(texel(t.view, 1.2f, 0.5f).r, 0.0);
    t.view.extension = TextureExtension::Mirror;
    EXPECT_DOUBLE_EQ(texel(t.view, 1.2f, 0.5f).r, 1.0);
    t.view.extension = TextureExtension::Clip;
    EXPECT_DOUBLE_EQ(texel(t.view, 1.2f, 0.5f).r, 0.0);
}

TEST(SurfaceTextures, ElementsTakeTheCheckersMeanOverTheirFootprints) {
    const double a = 0.2, b = 0.6;
    const OwnedTexture t = checker(4, a, b, TextureFilter::Closest);
    test::SceneArrays s;
    s.add_quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, Rgb(0.4));  // the checker's mean
    const Textured textured(s, t.view, false);
    SceneInput in = s.input();
    in.textures = &textured.textures;
    // Elements a third wide straddle the checker's squares.
    const Elements e = build_elements(in, 1.0f / 3.0f).elements;
    ASSERT_EQ(e.size(), 9u);
    for (std::size_t k = 0; k < e.size(); ++k) {
        double x0, x1, y0, y1;
        element_box(e, k, x0, x1, y0, y1);
        const double expected = checker_mean(4, a, b, x0, x1, y0, y1);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(e.reflectance[k][c], expected, 1e-6) << "element " << k;
    }
}

TEST(SurfaceTextures, ElementsTakeTheRampsMeanAlsoOnTriangles) {
    const OwnedTexture t = ramp(8);
    test::SceneArrays s;
    s.add_quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, Rgb(0.5));
    s.add_polygon({{1.2f, 0.1f, 0}, {1.8f, 0.2f, 0}, {1.5f, 0.9f, 0}}, Rgb(0.5), Rgb(0.0));
    const Textured textured(s, t.view, false);
    SceneInput in = s.input();
    in.textures = &textured.textures;
    const Elements e = build_elements(in, 0.25f).elements;
    const double lo = 1.0 / 16.0, hi = 15.0 / 16.0;
    std::size_t triangles = 0;
    for (std::size_t k = 0; k < e.size(); ++k) {
        double x0, x1, y0, y1;
        element_box(e, k, x0, x1, y0, y1);
        double expected;
        if (e.polygon[k] == 0) {
            expected = clamped_integral(x0, x1, lo, hi) / (x1 - x0);
        } else {
            expected = hi;  // the triangle's UV is its (x, y), beyond 1: Extend holds the last texel
            ++triangles;
        }
        EXPECT_NEAR(e.reflectance[k].g, expected, 1e-9) << "element " << k;
    }
    EXPECT_GT(triangles, 3u);
}

TEST(SurfaceTextures, TrianglesTakeTheValueAtTheirCentroidOnALinearRamp) {
    const OwnedTexture t = ramp(8);
    test::SceneArrays s;
    s.add_polygon({{0.2f, 0.1f, 0}, {0.8f, 0.2f, 0}, {0.5f, 0.9f, 0}}, Rgb(0.5), Rgb(0.0));
    const Textured textured(s, t.view, false);
    SceneInput in = s.input();
    in.textures = &textured.textures;
    const Elements e = build_elements(in, 0.2f).elements;
    ASSERT_GT(e.size(), 4u);
    for (std::size_t k = 0; k < e.size(); ++k)  // u = x inside [1/16, 15/16]: the mean is u at the centroid
        EXPECT_NEAR(e.reflectance[k].r, e.centre[k].x, 1e-6) << "element " << k;
}

TEST(SurfaceTextures, ElementsWiderThanSixtyFourTexelsReadAHalvedImageWithTheSameMean) {
    const OwnedTexture t = checker(256, 0.1, 0.7, TextureFilter::Closest);
    test::SceneArrays s;
    s.add_quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, Rgb(0.4));
    const Textured textured(s, t.view, false);
    SceneInput in = s.input();
    in.textures = &textured.textures;
    const Elements e = build_elements(in, 0.5f).elements;  // 128 texels across each
    ASSERT_EQ(e.size(), 4u);
    for (std::size_t k = 0; k < e.size(); ++k) EXPECT_NEAR(e.reflectance[k].b, 0.4, 1e-6);
}

TEST(SurfaceTextures, AnEmittingTextureGivesItsFlux) {
    const OwnedTexture t = ramp(8);
    test::SceneArrays s;
    // A 1 x 1 panel facing down at z = 1, emitting 5 x the ramp (its mean 0.5) from both sides.
    s.add_quad({0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}, Rgb(0.0), Rgb(2.5));
    Textured textured(s, t.view, true);
    std::fill(textured.scale.begin(), textured.scale.end(), 5.0f);
    SceneInput in = s.input();
    in.textures = &textured.textures;
    const Elements e = build_elements(in, 0.125f).elements;
    double front = 0.0, back = 0.0;
    for (std::size_t k = 0; k < e.size(); ++k) (e.is_back(k) ? back : front) += e.area[k] * e.emission[k].r;
    const double exact = 5.0 * clamped_integral(0.0, 1.0, 1.0 / 16.0, 15.0 / 16.0);  // the mean is exactly 0.5
    EXPECT_NEAR(front, exact, 1e-6);
    EXPECT_NEAR(back, exact, 1e-6);
}

TEST(SurfaceTextures, CornersShowTheTexelTimesTheLightArriving) {
    // A floor of four quads under a black square emitter: the light arriving at the floor is the
    // emitter's alone, whatever the floor's colour, so the textured floor's corners must be the
    // texel there times the light the untextured floor's corners receive.
    OwnedTexture t(4, 4, TextureFilter::Linear, TextureExtension::Extend);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) t.set(x, y, 0.1 + 0.2 * x + 0.02 * y);
    test::SceneArrays s;
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
            const float x = 0.5f * i, y = 0.5f * j;  // each face's colour: the texture's mean, 0.43
            s.add_quad({x, y, 0}, {x + 0.5f, y, 0}, {x + 0.5f, y + 0.5f, 0}, {x, y + 0.5f, 0}, Rgb(0.43));
        }
    s.add_quad({0.25f, 0.25f, 1}, {0.25f, 0.75f, 1}, {0.75f, 0.75f, 1}, {0.75f, 0.25f, 1}, Rgb(0.0), Rgb(3.0), 1);
    Textured textured(s, t.view, false);
    textured.index.back() = -1;  // the emitter is not textured
    BakeSettings settings;
    settings.element_size = 0.125f;
    settings.final_gather.enabled = true;
    const BakeResult plain = bake(s.input(), settings);
    SceneInput in = s.input();
    in.textures = &textured.textures;
    const BakeResult result = bake(in, settings);
    for (std::size_t c = 0; c < 16; ++c) {  // the floor's corners
        const Rgb expected =
            texel(t.view, textured.uv[2 * c], textured.uv[2 * c + 1]) * plain.light_colors.input_corner[c];
        for (int k = 0; k < 3; ++k)  // to float precision: the face's mean colour is a float
            EXPECT_NEAR(result.colors.input_corner[c][k], expected[k], 1e-6 * expected[k]) << "corner " << c;
        EXPECT_NEAR(result.light_colors.input_corner[c].g, plain.light_colors.input_corner[c].g, 1e-9);
    }
    // The texture's colour shows: corner 0 (u = 0, texel 0.1) against corner 1 (u = 0.5, texel 0.4).
    EXPECT_LT(result.colors.input_corner[0].r / plain.light_colors.input_corner[0].r,
              result.colors.input_corner[1].r / plain.light_colors.input_corner[1].r);
}

TEST(SurfaceTextures, HierarchicalLeavesTakeTheirOwnMeanAndCornersTheTexel) {
    // A floor under a point lamp, alone: the light arriving anywhere on it is the lamp's,
    // I cos / (pi r^2), whatever its colour. The lamp's light splits leaves down to 1/16 of the
    // floor, inside the checker's squares (1/4): each such leaf reflects its square's colour, and
    // every corner shows the texel there times the light arriving.
    const double a = 0.2, b = 0.6;
    const OwnedTexture t = checker(4, a, b, TextureFilter::Closest);
    test::SceneArrays s;
    s.add_quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, Rgb(0.4));  // the checker's mean
    const Textured textured(s, t.view, false);
    SceneInput in = s.input();
    in.textures = &textured.textures;
    BakeSettings settings;
    settings.hierarchical.enabled = true;
    settings.element_size = 0.25f;
    PointLight lamp;
    lamp.position = Vec3(0.4f, 0.55f, 0.3f);
    lamp.intensity = Rgb(1.0);
    settings.lights.points.push_back(lamp);
    const BakeResult r = bake(in, settings);
    const Elements& e = r.build.elements;
    std::size_t inside_a_square = 0;
    for (std::size_t k = 0; k < e.size(); ++k) {
        double x0, x1, y0, y1;
        element_box(e, k, x0, x1, y0, y1);
        if (x1 - x0 > 0.25 + 1e-6 || y1 - y0 > 0.25 + 1e-6) continue;
        ++inside_a_square;
        EXPECT_NEAR(e.reflectance[k].g, checker_mean(4, a, b, x0, x1, y0, y1), 1e-6) << "element " << k;
    }
    EXPECT_GT(inside_a_square, 16u);
    auto arriving = [&](const Vec3& x) {
        const Vec3 d = lamp.position - x;
        const double r2 = glm::dot(d, d);
        return d.z / std::sqrt(r2) / (M_PI * r2);
    };
    for (std::size_t k = 0; k < e.size(); ++k)
        for (int c = 0; c < e.corner_count(k); ++c) {
            const Vec3 x = e.vertices[e.corners[k][c]];
            const double light = arriving(x);
            EXPECT_NEAR(r.light_colors.element_corner[4 * k + c].g, light, 1e-3 * light) << "element " << k;
            EXPECT_NEAR(r.colors.element_corner[4 * k + c].g, texel(t.view, x.x, x.y).g * light, 1e-3 * light)
                << "element " << k;
        }
    for (std::size_t c = 0; c < 4; ++c) {
        const float u = textured.uv[2 * c], v = textured.uv[2 * c + 1];
        EXPECT_NEAR(r.colors.input_corner[c].g, texel(t.view, u, v).g * r.light_colors.input_corner[c].g, 1e-6);
    }
}

}  // namespace
}  // namespace radiosity
