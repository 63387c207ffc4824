/// @file test_point_light.cpp
/// @brief Point lamps with a radius against integrals over their sphere or disk: the near field,
/// the horizon, a half-hidden lamp and one hidden by the face beside a corner.
#include "transport/cone.h"
#include "transport/point_light.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <cmath>
#include <functional>
#include <memory>

namespace radiosity {
namespace {

constexpr double kIntensity = 2.0;

PointLight lamp(LampShape shape, Vec3 position, float radius) {
    PointLight l;
    l.position = position;
    l.intensity = Rgb(kIntensity);
    l.radius = radius;
    l.shape = shape;
    return l;
}

/// A Visibility whose only patch is `corners` (a quad); by default a speck far away: nothing hides.
std::unique_ptr<hr::Visibility> scene_of(std::vector<Vec3> corners = {{100, 100, 100},
                                                                      {100.001f, 100, 100},
                                                                      {100.001f, 100.001f, 100},
                                                                      {100, 100.001f, 100}}) {
    return std::make_unique<hr::Visibility>(corners, std::vector<std::array<int32_t, 4>>{{0, 1, 2, 3}}, 2.0f);
}

/// The irradiance at `x` (normal +z) from a uniform radiance over the sphere's surface facing x,
/// by the midpoint rule over its polar angle and azimuth: sum of L cos_x cos_y / t^2 dA.
double sphere_by_surface(const PointLight& l, const glm::dvec3& x) {
    constexpr int kPolar = 1500, kAzimuth = 3000;
    const double r = l.radius, L = kIntensity / (M_PI * r * r);
    double sum = 0.0;
    for (int i = 0; i < kPolar; ++i) {
        const double theta = (i + 0.5) * M_PI / kPolar;
        for (int j = 0; j < kAzimuth; ++j) {
            const double phi = (j + 0.5) * 2.0 * M_PI / kAzimuth;
            const glm::dvec3 n(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
            const glm::dvec3 d = glm::dvec3(l.position) + r * n - x;
            const double t = glm::length(d), cos_x = d.z / t, cos_y = -glm::dot(n, d) / t;
            if (cos_x > 0.0 && cos_y > 0.0) sum += L * cos_x * cos_y / (t * t) * r * r * std::sin(theta);
        }
    }
    return sum * (M_PI / kPolar) * (2.0 * M_PI / kAzimuth);
}

/// The irradiance at `x` (normal +z) from the lamp's disk facing x, by the midpoint rule over the
/// disk: sum of L cos_x cos_y / t^2 dA.
double disk_by_area(const PointLight& l, const glm::dvec3& x) {
    constexpr int kRadial = 1500, kAzimuth = 3000;
    const double r = l.radius, L = kIntensity / (M_PI * r * r);
    const glm::dvec3 c(l.position), axis = glm::normalize(x - c);
    const glm::dvec3 t =
        glm::normalize(glm::cross(std::abs(axis.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0), axis));
    const glm::dvec3 b = glm::cross(axis, t);
    double sum = 0.0;
    for (int i = 0; i < kRadial; ++i) {
        const double rho = (i + 0.5) * r / kRadial;
        for (int j = 0; j < kAzimuth; ++j) {
            const double phi = (j + 0.5) * 2.0 * M_PI / kAzimuth;
            const glm::dvec3 d = c + rho * (std::cos(phi) * t + std::sin(phi) * b) - x;
            const double dist = glm::length(d), cos_x = d.z / dist, cos_y = -glm::dot(axis, d) / dist;
            if (!(cos_x > 0.0)) continue;
            sum += L * cos_x * cos_y / (dist * dist) * rho;
        }
    }
    return sum * (r / kRadial) * (2.0 * M_PI / kAzimuth);
}

double unshadowed(const PointLight& l, Vec3 x) { return point_unshadowed(l, x, Vec3(0, 0, 1)).r; }

double traced(const PointLight& l, Vec3 x, const hr::Visibility& v) {
    return point_irradiance(l, v, x, Vec3(0, 0, 1), point_rays(l, x), 7U).r;
}

TEST(PointLight, SphereAboveTheHorizonLightsAsAPointAtItsCentre) {
    const PointLight l = lamp(LampShape::Sphere, Vec3(0.1f, 0.05f, 0.3f), 0.05f);
    const glm::dvec3 p(l.position);
    const double d2 = glm::dot(p, p), truth = kIntensity * p.z / std::sqrt(d2) / d2;
    EXPECT_NEAR(unshadowed(l, Vec3(0)), truth, 1e-12 * truth);
}

TEST(PointLight, SphereNearAWallMatchesTheIntegralOverItsSurface) {
    const auto nothing = scene_of();
    for (float height : {0.03f, 0.1f, 0.5f}) {
        const PointLight l = lamp(LampShape::Sphere, Vec3(0, 0, height), 0.05f);
        for (float offset : {0.0f, 0.045f, 0.08f, 0.15f, 0.3f, 1.0f}) {
            const Vec3 x(offset, 0, 0);
            if (glm::length(l.position - x) < l.radius) continue;  // inside: the next test
            const double truth = sphere_by_surface(l, glm::dvec3(x));
            EXPECT_NEAR(unshadowed(l, x), truth, 1e-3 * truth) << height << " " << offset;
            EXPECT_NEAR(traced(l, x, *nothing), truth, 1e-3 * truth) << height << " " << offset;
        }
    }
}

TEST(PointLight, InsideASphereTheWholeHemisphereShines) {
    const PointLight l = lamp(LampShape::Sphere, Vec3(0, 0, 0.03f), 0.05f);
    const double r = l.radius;
    EXPECT_NEAR(unshadowed(l, Vec3(0.02f, 0, 0)), kIntensity / (r * r), 1e-12 / (r * r));
}

TEST(PointLight, DiskFacingThePointMatchesTheIntegralOverIt) {
    const auto nothing = scene_of();
    const PointLight on_axis = lamp(LampShape::Disk, Vec3(0, 0, 0.03f), 0.05f);
    const double h = on_axis.position.z, r = on_axis.radius;
    EXPECT_NEAR(unshadowed(on_axis, Vec3(0)), kIntensity / (h * h + r * r), 1e-12 / (h * h + r * r));
    for (float height : {0.03f, 0.1f}) {
        const PointLight l = lamp(LampShape::Disk, Vec3(0, 0, height), 0.05f);
        for (float offset : {0.02f, 0.06f, 0.15f}) {
            const Vec3 x(offset, 0, 0);
            const double truth = disk_by_area(l, glm::dvec3(x));
            EXPECT_NEAR(unshadowed(l, x), truth, 2e-3 * truth) << height << " " << offset;
            EXPECT_NEAR(traced(l, x, *nothing), truth, 2e-3 * truth) << height << " " << offset;
        }
    }
}

/// The light from every direction (a medium's, lamps_in_media.h): the lamp's radiance I / (pi r^2)
/// times the solid angle it fills, integrated here over the disk's area (d A cos / s^2 in rings) and
/// over the sphere's cone of directions; far away both are a point's I / d^2, and a spot's profile
/// scales them.
TEST(PointLight, FluenceIsTheRadianceTimesTheSolidAngleTheLampFills) {
    const double r = 0.05, radiance = kIntensity / (M_PI * r * r);
    for (double d : {0.02, 0.05, 0.1, 1.0}) {
        const int n = 20000;
        double disk = 0.0, sphere = 0.0;
        for (int i = 0; i < n; ++i) {
            const double rho = (i + 0.5) * r / n;  // a ring of the disk, facing the point
            disk += 2.0 * M_PI * rho * (r / n) * d / std::pow(d * d + rho * rho, 1.5);
            if (d > r) {
                const double alpha = std::asin(r / d), theta = (i + 0.5) * alpha / n;
                sphere += 2.0 * M_PI * std::sin(theta) * (alpha / n);
            }
        }
        const Vec3 x(0.0f, 0.0f, float(d));
        EXPECT_NEAR(point_fluence(lamp(LampShape::Disk, Vec3(0), float(r)), x).g / (radiance * disk), 1.0, 1e-6) << d;
        if (d > r)
            EXPECT_NEAR(point_fluence(lamp(LampShape::Sphere, Vec3(0), float(r)), x).g / (radiance * sphere), 1.0, 1e-6)
                << d;
    }
    EXPECT_NEAR(point_fluence(lamp(LampShape::Sphere, Vec3(0), float(r)), Vec3(0.01f, 0, 0)).g, 4.0 * M_PI * radiance,
                1e-6 * 4.0 * M_PI * radiance);
    const Vec3 far(0.0f, 0.0f, -10.0f);
    for (float radius : {0.0f, float(r)})
        for (LampShape shape : {LampShape::Disk, LampShape::Sphere})
            EXPECT_NEAR(point_fluence(lamp(shape, Vec3(0), radius), far).r, kIntensity / 100.0,
                        1e-4 * kIntensity / 100.0);
    PointLight spot = lamp(LampShape::Disk, Vec3(0), float(r));
    spot.cos_half_angle = 0.5f;
    spot.smooth = 0.2f;
    const Vec3 off_axis = glm::normalize(Vec3(0.4f, 0.0f, -1.0f));
    EXPECT_NEAR(point_fluence(spot, 10.0f * off_axis).b,
                spot_profile(spot, off_axis) * point_fluence(lamp(LampShape::Disk, Vec3(0), float(r)), far).b,
                1e-6 * 0.02);
}

TEST(PointLight, AHalfHiddenLampGivesHalfItsLight) {
    // A shelf at z = 0.05 over x > 0 hides the half of the lamp's cone with x > 0 from the origin.
    const auto shelf = scene_of({{0, -1, 0.05f}, {1, -1, 0.05f}, {1, 1, 0.05f}, {0, 1, 0.05f}});
    for (LampShape shape : {LampShape::Sphere, LampShape::Disk}) {
        const PointLight l = lamp(shape, Vec3(0, 0, 0.1f), 0.05f);
        const double whole = traced(l, Vec3(0), *scene_of());
        EXPECT_NEAR(traced(l, Vec3(0), *shelf), whole / 2, 0.02 * whole / 2) << int(shape);
    }
}

TEST(PointLight, TheFaceBesideACornerHidesAFarLamp) {
    // A wall facing +x meets a roof (z = 0, over x in [0, 1]) at the corner where Cycles bakes it:
    // 0.5 mm from the wall and 0.4 mm under the roof. A lamp 8.5 m away up and out from the wall is
    // behind the roof seen from there. Rays that left a gap of a ten-thousandth of their length
    // (0.85 mm) passed through the roof and lit the point.
    const auto roof = scene_of({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
    const Vec3 x(0.0005f, 0.5f, -0.0004f), wall_normal(1, 0, 0);
    for (const float radius : {0.0f, 0.05f}) {
        const PointLight l = lamp(LampShape::Sphere, Vec3(3, 0.5f, 8), radius);
        ASSERT_GT(max_channel(point_unshadowed(l, x, wall_normal)), 0.0);
        EXPECT_EQ(max_channel(point_irradiance(l, *roof, x, wall_normal, 64, 7)), 0.0) << radius;
        EXPECT_GT(max_channel(point_irradiance(l, *scene_of(), x, wall_normal, 64, 7)), 0.0) << radius;
    }
}

TEST(PointLight, WithoutRadiusItIsInverseSquareAndCosine) {
    const PointLight l = lamp(LampShape::Disk, Vec3(0.3f, 0, 1), 0.0f);
    const double d2 = 0.09 + 1.0;
    EXPECT_NEAR(traced(l, Vec3(0), *scene_of()), kIntensity / d2 / std::sqrt(d2), 1e-7);
    EXPECT_EQ(point_rays(l, Vec3(0)), 1);
}

TEST(PointLight, PolygonGetsThePowerThroughItsSolidAngle) {
    // A square [-1, 1]^2 seen from 1 above its centre: solid angle 2 pi / 3 (a cube's face).
    const PointLight l = lamp(LampShape::Sphere, Vec3(0, 0, 1), 0.05f);
    const Vec3 square[4] = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    EXPECT_NEAR(point_polygon_unshadowed(l, square, 4, Vec3(0, 0, 1), 4.0).r, kIntensity * (2 * M_PI / 3) / 4.0, 1e-9);
    EXPECT_EQ(point_polygon_unshadowed(l, square, 4, Vec3(0, 0, -1), 4.0).r, 0.0);  // its back
}

/// The mean of the lamp's unshadowed light (point_unshadowed, checked against the integrals above)
/// over the square [-half, half]^2 at z = 0, by the midpoint rule.
double square_mean(const PointLight& l, double half) {
    constexpr int kCells = 400;
    double sum = 0.0;
    for (int i = 0; i < kCells; ++i)
        for (int j = 0; j < kCells; ++j)
            sum += unshadowed(l, Vec3(float(half * (2.0 * (i + 0.5) / kCells - 1.0)),
                                      float(half * (2.0 * (j + 0.5) / kCells - 1.0)), 0.0f));
    return sum / (kCells * kCells);
}

TEST(PointLight, PolygonNearALampGetsTheLightOfItsDiskOrSphere) {
    // A shade's 16 cm side 8 cm from a 5 cm lamp, and a 50 cm floor element 6 cm under it: the disk
    // gives 0.72 of a point's light under it; a sphere above the plane a point's.
    for (LampShape shape : {LampShape::Disk, LampShape::Sphere}) {
        for (const auto& [height, half] : {std::pair{0.08, 0.08}, std::pair{0.06, 0.25}, std::pair{1.0, 0.25}}) {
            const PointLight l = lamp(shape, Vec3(0.01f, -0.02f, float(height)), 0.05f);
            const Vec3 square[4] = {Vec3(-half, -half, 0), Vec3(half, -half, 0), Vec3(half, half, 0),
                                    Vec3(-half, half, 0)};
            const double truth = square_mean(l, half);
            EXPECT_NEAR(point_polygon_unshadowed(l, square, 4, Vec3(0, 0, 1), 4 * half * half).r, truth, 5e-3 * truth)
                << int(shape) << " " << height << " " << half;
        }
    }
}

}  // namespace
}  // namespace radiosity
