/// @file test_sun_light.cpp
/// @brief Sun lamps with an angle against the mean cosine over their cone, as each Cycles spreads
/// it, and their shadows.
#include "transport/cone.h"
#include "transport/sun_light.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <cmath>
#include <memory>

namespace radiosity {
namespace {

std::unique_ptr<hr::Visibility> scene_of(std::vector<Vec3> corners) {
    return std::make_unique<hr::Visibility>(corners, std::vector<std::array<int32_t, 4>>{{0, 1, 2, 3}}, 2.0f);
}

std::unique_ptr<hr::Visibility> nothing() {
    return scene_of({{100, 100, 100}, {100.001f, 100, 100}, {100.001f, 100.001f, 100}, {100, 100.001f, 100}});
}

SunLight sun(float half_angle, bool disk_directions) {
    SunLight s;
    s.direction = Vec3(0, 0, -1);
    s.irradiance = Rgb(3.0);
    s.half_angle = half_angle;
    s.disk_directions = disk_directions;
    return s;
}

double at(const SunLight& s, const hr::Visibility& v, Vec3 normal) {
    return sun_irradiance(s, v, Vec3(0), normal, sun_rays(s), 11U).r;
}

TEST(SunLight, FacingItGivesTheMeanCosineOfItsDirections) {
    const auto v = nothing();
    const double a = 0.5;  // half-angle; Cycles 4.x: cos theta uniform, mean (1 + cos a) / 2
    EXPECT_NEAR(at(sun(float(a), false), *v, Vec3(0, 0, 1)), 3.0 * (1.0 + std::cos(a)) / 2.0, 2e-4);
    // Cycles 3.x: uniform over a disk of radius R = tan a one unit out: mean 2 (sqrt(1 + R^2) - 1) / R^2.
    const double R = std::tan(a);
    EXPECT_NEAR(at(sun(float(a), true), *v, Vec3(0, 0, 1)), 3.0 * 2.0 * (std::sqrt(1.0 + R * R) - 1.0) / (R * R), 2e-4);
    EXPECT_NEAR(at(sun(0.0f, false), *v, Vec3(0, 0, 1)), 3.0, 1e-12);
}

TEST(SunLight, AtTheHorizonOnlyThePartAboveLights) {
    const auto v = nothing();
    const double a = 0.3;
    for (double tilt : {1.4, 1.57, 1.75}) {  // the cone's axis that far from the normal
        const Vec3 normal(float(std::sin(tilt)), 0.0f, float(std::cos(tilt)));
        const double truth = 3.0 * detail::clipped_cone_cosine(std::cos(tilt), std::sin(a) * std::sin(a)) /
                             (2.0 * M_PI * (1.0 - std::cos(a)));
        EXPECT_NEAR(at(sun(float(a), false), *v, normal), truth, 1e-6) << tilt;  // float normal
    }
}

TEST(SunLight, AnEdgeOverThePointHidesHalfTheSun) {
    const auto shelf = scene_of({{0, -1, 0.5f}, {1, -1, 0.5f}, {1, 1, 0.5f}, {0, 1, 0.5f}});
    const SunLight s = sun(0.2f, false);
    const double whole = at(s, *nothing(), Vec3(0, 0, 1));
    EXPECT_NEAR(at(s, *shelf, Vec3(0, 0, 1)), whole / 2, 0.03 * whole / 2);
    const auto roof = scene_of({{-1, -1, 0.5f}, {1, -1, 0.5f}, {1, 1, 0.5f}, {-1, 1, 0.5f}});
    EXPECT_EQ(at(s, *roof, Vec3(0, 0, 1)), 0.0);
}

}  // namespace
}  // namespace radiosity
