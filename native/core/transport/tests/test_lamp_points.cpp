/// @file test_lamp_points.cpp
/// @brief Hundreds of lamps at a point: the lamps that matter traced, the rest picked, against
/// the sum over every lamp; a few dozen all traced.
#include "transport/lamp_points.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace radiosity {
namespace {

/// 500 white lamps of radius 0 and 2 cm scattered through a 10 x 10 x 3 m room.
Lights many_lamps() {
    Lights lights;
    std::mt19937 random(5);
    std::uniform_real_distribution<float> along(0.0f, 10.0f), up(0.3f, 2.9f);
    for (int i = 0; i < 500; ++i) {
        PointLight lamp;
        lamp.position = Vec3(along(random), along(random), up(random));
        lamp.intensity = Rgb(1.0 + (i % 7));
        lamp.radius = i % 2 ? 0.02f : 0.0f;
        lights.points.push_back(lamp);
    }
    return lights;
}

/// Floor points on a 20 x 20 grid.
std::vector<Vec3> floor_points() {
    std::vector<Vec3> points;
    for (int i = 0; i < 20; ++i)
        for (int j = 0; j < 20; ++j) points.emplace_back(0.25f + 0.5f * i, 0.25f + 0.5f * j, 0.0f);
    return points;
}

TEST(LampPoints, WhenNothingHidesThemHundredsOfLampsSumExactly) {
    const Lights lights = many_lamps();
    const hr::Visibility open({{100, 100, 100}, {100.01f, 100, 100}, {100.01f, 100.01f, 100}, {100, 100.01f, 100}},
                              {{0, 1, 2, 3}}, 20.0f);
    for (const Vec3& x : floor_points()) {
        double truth = 0.0;
        for (const PointLight& lamp : lights.points) truth += point_unshadowed(lamp, x, Vec3(0, 0, 1)).r;
        EXPECT_NEAR(detail::lamp_irradiance(lights, open, x, Vec3(0, 0, 1)).r, truth, 1e-9 * truth);
    }
}

TEST(LampPoints, AWallHidingHalfTheLampsIsMetOnAverage) {
    const Lights lights = many_lamps();
    const hr::Visibility wall({{5, -1, -1}, {5, 11, -1}, {5, 11, 4}, {5, -1, 4}}, {{0, 1, 2, 3}}, 20.0f);
    double sum = 0.0, truth = 0.0;
    for (const Vec3& x : floor_points()) {
        sum += detail::lamp_irradiance(lights, wall, x, Vec3(0, 0, 1)).r;
        for (const PointLight& lamp : lights.points)
            if ((lamp.position.x > 5) == (x.x > 5)) truth += point_unshadowed(lamp, x, Vec3(0, 0, 1)).r;
    }
    EXPECT_NEAR(sum, truth, 0.01 * truth);
}

TEST(LampPoints, APointInTheShadowOfItsBrightestLampsTakesTheDimOnesThatReachItExactly) {
    // 8 bright lamps behind a wall at x = 5 give 98% of the unshadowed light on the floor before
    // it; the 40 dim ones in front of it, each under kTracedShare of the total, are all that reach it.
    Lights lights;
    std::mt19937 random(11);
    std::uniform_real_distribution<float> front(0.2f, 4.8f), behind(5.2f, 9.8f), along(0.0f, 10.0f), up(0.3f, 2.9f);
    for (int i = 0; i < 48; ++i) {
        PointLight lamp;
        const bool bright = i < 8;
        lamp.position = Vec3(bright ? behind(random) : front(random), along(random), up(random));
        lamp.intensity = Rgb(bright ? 50000.0 : 1.0);
        lights.points.push_back(lamp);
    }
    const hr::Visibility wall({{5, -1, -1}, {5, 11, -1}, {5, 11, 4}, {5, -1, 4}}, {{0, 1, 2, 3}}, 20.0f);
    for (const Vec3& x : floor_points()) {
        if (x.x > 5) continue;
        double truth = 0.0, all = 0.0;
        for (const PointLight& lamp : lights.points) {
            const double u = point_unshadowed(lamp, x, Vec3(0, 0, 1)).r;
            all += u;
            if (lamp.position.x < 5) truth += u;
        }
        ASSERT_LT(truth, 0.05 * all);
        EXPECT_NEAR(detail::lamp_irradiance(lights, wall, x, Vec3(0, 0, 1)).r, truth, 1e-9 * truth)
            << x.x << " " << x.y;
    }
}

}  // namespace
}  // namespace radiosity
