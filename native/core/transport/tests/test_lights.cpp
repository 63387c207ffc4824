/// @file test_lights.cpp
/// @brief Direct light from lamps against the inverse-square law, Lambert's cosine and shadows.
#include "testing/test_util.h"
#include "transport/lights.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <cmath>

namespace radiosity {
namespace {

/// A square floor [-half, half]^2 at z = 0 facing up, split into elements of `element` metres.
test::SceneArrays floor_scene(float half) {
    test::SceneArrays s;
    s.add_quad({-half, -half, 0}, {half, -half, 0}, {half, half, 0}, {-half, half, 0}, Rgb(0.5));
    return s;
}

/// Index of the element whose centre is nearest to (x, y) on the floor.
std::size_t element_at(const Elements& elements, float x, float y) {
    std::size_t best = 0;
    float best_d = INFINITY;
    for (std::size_t e = 0; e < elements.size(); ++e) {
        const float d = std::hypot(elements.centre[e].x - x, elements.centre[e].y - y);
        if (d < best_d) best_d = d, best = e;
    }
    return best;
}

/// Exact mean irradiance of an isotropic point lamp at height h over the square element [x0,x1]x[y0,y1]:
/// the solid angle of the square from the lamp times I, over the area (the integral of I h / r^3).
double exact_mean_irradiance(double I, double h, double x0, double x1, double y0, double y1) {
    auto corner = [h](double x, double y) { return std::atan(x * y / (h * std::sqrt(x * x + y * y + h * h))); };
    const double solid_angle = corner(x1, y1) - corner(x0, y1) - corner(x1, y0) + corner(x0, y0);
    return I * solid_angle / ((x1 - x0) * (y1 - y0));
}

// Per element, counting cube cells aliases: an element about 20 x 13 cells wide (the farthest one
// below, at resolution 1024) can be off by about half its perimeter in cells over its area, ~5%.
// The floor as a whole has no such error: the lamp's power is conserved.
TEST(PointLight, InverseSquareAndCosine) {
    const auto scene = floor_scene(2.0f);
    const auto elements = build_elements(scene.input(), 0.1f).elements;
    Lights lights;
    lights.resolution = 1024;
    const double I = 10.0, h = 1.5;
    lights.points.push_back({Vec3(0, 0, float(h)), Rgb(I)});
    const auto E = direct_irradiance(elements, lights);
    for (auto [x, y] : {std::pair{0.05f, 0.05f}, {0.75f, 0.05f}, {1.45f, 1.05f}}) {
        const std::size_t e = element_at(elements, x, y);
        const Vec3 c = elements.centre[e];
        const double exact = exact_mean_irradiance(I, h, c.x - 0.05, c.x + 0.05, c.y - 0.05, c.y + 0.05);
        EXPECT_NEAR(E[e].r, exact, 0.05 * exact) << "element at " << x << ", " << y;
    }
    // Power conservation: the floor catches the lamp's flux over the solid angle the floor subtends.
    double flux = 0.0;
    for (std::size_t e = 0; e < elements.size(); ++e) flux += E[e].g * elements.area[e];
    EXPECT_NEAR(flux, exact_mean_irradiance(I, h, -2, 2, -2, 2) * 16.0, 1e-3 * flux);
}

TEST(PointLight, BlockerCastsShadowAndBackSideGetsNothing) {
    auto scene = floor_scene(2.0f);
    // A blocker 0.5 m above the floor, facing up (towards the lamp), over [-0.5, 0.5]^2.
    scene.add_quad({-0.5f, -0.5f, 0.5f}, {0.5f, -0.5f, 0.5f}, {0.5f, 0.5f, 0.5f}, {-0.5f, 0.5f, 0.5f}, Rgb(0.5));
    const auto elements = build_elements(scene.input(), 0.1f).elements;
    Lights lights;
    lights.resolution = 256;
    lights.points.push_back({Vec3(0, 0, 2), Rgb(5.0)});
    const auto E = direct_irradiance(elements, lights);
    std::size_t under = 0, blocker = 0;
    for (std::size_t e = 0; e < elements.size(); ++e) {
        const Vec3 c = elements.centre[e];
        if (c.z < 0.25f && std::abs(c.x) < 0.4f && std::abs(c.y) < 0.4f) {
            EXPECT_EQ(E[e].r, 0.0);
            ++under;
        }
        if (c.z > 0.25f) {
            EXPECT_GT(E[e].r, 0.0);
            ++blocker;
        }
    }
    EXPECT_GT(under, 0u);
    EXPECT_GT(blocker, 0u);

    // The same blocker turned over (facing away from the lamp) still shadows, and receives nothing.
    test::SceneArrays flipped = floor_scene(2.0f);
    flipped.add_quad({-0.5f, -0.5f, 0.5f}, {-0.5f, 0.5f, 0.5f}, {0.5f, 0.5f, 0.5f}, {0.5f, -0.5f, 0.5f}, Rgb(0.5));
    const auto flipped_elements = build_elements(flipped.input(), 0.1f).elements;
    const auto F = direct_irradiance(flipped_elements, lights);
    for (std::size_t e = 0; e < flipped_elements.size(); ++e) {
        const Vec3 c = flipped_elements.centre[e];
        if (c.z > 0.25f || (std::abs(c.x) < 0.4f && std::abs(c.y) < 0.4f)) EXPECT_EQ(F[e].r, 0.0);
    }
}

TEST(SpotLight, ConeAndCyclesFalloff) {
    PointLight spot{Vec3(0, 0, 1), Rgb(1.0), Vec3(0, 0, -1), std::cos(0.5f), 0.0f};
    EXPECT_FLOAT_EQ(spot_profile(spot, glm::normalize(Vec3(0, 0, -1))), 1.0f);
    const Vec3 inside = glm::normalize(Vec3(std::sin(0.4f), 0, -std::cos(0.4f)));
    EXPECT_NEAR(spot_profile(spot, inside), std::cos(0.4f), 1e-6);  // Cycles keeps the cosine
    EXPECT_EQ(spot_profile(spot, glm::normalize(Vec3(std::sin(0.6f), 0, -std::cos(0.6f)))), 0.0f);
    spot.smooth = (1.0f - spot.cos_half_angle) * 0.5f;
    const float t = (std::cos(0.4f) - spot.cos_half_angle) / spot.smooth, s = t * t * (3 - 2 * t);
    EXPECT_NEAR(spot_profile(spot, inside), std::cos(0.4f) * s, 1e-6);
    spot.cosine_profile = false;  // Cycles 4.0 and later: the smoothstep alone
    EXPECT_NEAR(spot_profile(spot, inside), s, 1e-6);
    EXPECT_FLOAT_EQ(spot_profile(spot, glm::normalize(Vec3(0, 0, -1))), 1.0f);

    // On the floor: nothing outside the cone, the profile times the point law inside.
    const auto scene = floor_scene(2.0f);
    const auto elements = build_elements(scene.input(), 0.1f).elements;
    Lights lights;
    lights.resolution = 512;
    lights.points.push_back({Vec3(0, 0, 1), Rgb(4.0), Vec3(0, 0, -1), std::cos(0.5f), 0.0f});
    const auto E = direct_irradiance(elements, lights);
    for (std::size_t e = 0; e < elements.size(); ++e) {
        const float r = std::hypot(elements.centre[e].x, elements.centre[e].y);
        if (r > std::tan(0.5f) + 0.08f) EXPECT_EQ(E[e].r, 0.0);
    }
    const std::size_t centre = element_at(elements, 0.05f, 0.05f);
    EXPECT_NEAR(E[centre].r, exact_mean_irradiance(4.0, 1.0, 0, 0.1, 0, 0.1), 0.03 * E[centre].r);
}

TEST(SunLight, LambertCosineAndShadow) {
    auto scene = floor_scene(1.0f);
    scene.add_quad({-0.2f, -0.2f, 0.3f}, {0.2f, -0.2f, 0.3f}, {0.2f, 0.2f, 0.3f}, {-0.2f, 0.2f, 0.3f}, Rgb(0.5));
    const auto elements = build_elements(scene.input(), 0.1f).elements;
    const float theta = 0.6f;
    Lights lights;
    lights.resolution = 1024;
    lights.suns.push_back({Vec3(std::sin(theta), 0, -std::cos(theta)), Rgb(3.0)});
    const auto E = direct_irradiance(elements, lights);
    const double lit = 3.0 * std::cos(theta);
    // The blocker's shadow lands shifted by 0.3 tan(theta) along +x.
    const float shift = 0.3f * std::tan(theta);
    std::size_t shadowed = 0;
    for (std::size_t e = 0; e < elements.size(); ++e) {
        const Vec3 c = elements.centre[e];
        const bool in_shadow = c.z < 0.1f && std::abs(c.x - shift) < 0.1f && std::abs(c.y) < 0.1f;
        const bool clear = c.z > 0.1f || std::abs(c.x - shift) > 0.35f || std::abs(c.y) > 0.35f;
        if (in_shadow) {
            EXPECT_EQ(E[e].r, 0.0);
            ++shadowed;
        }
        if (clear) EXPECT_NEAR(E[e].r, lit, 1e-5 * lit);
    }
    EXPECT_GT(shadowed, 0u);
}

}  // namespace
}  // namespace radiosity
