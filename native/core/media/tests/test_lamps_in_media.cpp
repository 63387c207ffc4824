/// @file test_lamps_in_media.cpp
/// @brief Lamps in a bake with media against closed forms and exact balances: the light a fog cube
/// takes up from a lamp inside it (integrated over directions by another route), one zone near and
/// one far from the lamp, a spot's cone, the zones near a lamp with a radius, a sun through the fog's top, the light on
/// walls through the fog, and a closed box whose walls and fog reflect alike, where everything the lamp sends is
/// absorbed after rho / (1 - rho) times as much has been reflected.
#include "bake/media_bake.h"
#include "media/lamps_in_media.h"
#include "testing/test_util.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <cmath>
#include <functional>

using namespace radiosity;

namespace {

constexpr double kK = 1.2;              // extinction of the fog, 1/m
const Vec3 kLamp(0.93f, 1.04f, 0.87f);  // off every voxel boundary, inside the 2 m cube

/// A 2 m cube of grey fog, 16^3 voxels of 0.125 m, its corner at the origin.
Medium fog_cube(double albedo) {
    Medium m(Vec3(0.0f), 0.125f, {16, 16, 16});
    for (std::size_t v = 0; v < m.voxel_count(); ++v) {
        m.extinction[v] = Rgb(kK);
        m.albedo[v] = Rgb(albedo);
    }
    return m;
}

/// Distance from `x` inside the box [lo, hi] along unit `d` to its boundary.
double exit_distance(const glm::dvec3& x, const glm::dvec3& d, const glm::dvec3& lo, const glm::dvec3& hi) {
    double t = INFINITY;
    for (int a = 0; a < 3; ++a) {
        if (d[a] > 0.0) t = std::min(t, (hi[a] - x[a]) / d[a]);
        if (d[a] < 0.0) t = std::min(t, (lo[a] - x[a]) / d[a]);
    }
    return t;
}

/// Integral over all directions of (1 - exp(-K l)), l the distance from `x` to the boundary of the
/// box [lo, hi], each direction weighted by `profile` (1 without): the fraction of a unit lamp's light
/// that box of fog takes up, times 4 pi. A midpoint rule in (cos theta, phi), not the code's lattice.
double taken_up_over_directions(const glm::dvec3& x, const glm::dvec3& lo, const glm::dvec3& hi,
                                const std::function<double(const glm::dvec3&)>& profile = {}) {
    const int n_z = 1500, n_phi = 3000;
    double sum = 0.0;
    for (int i = 0; i < n_z; ++i) {
        const double z = -1.0 + (i + 0.5) * 2.0 / n_z, r = std::sqrt(1.0 - z * z);
        for (int j = 0; j < n_phi; ++j) {
            const double phi = (j + 0.5) * 2.0 * M_PI / n_phi;
            const glm::dvec3 d(r * std::cos(phi), r * std::sin(phi), z);
            sum += (profile ? profile(d) : 1.0) * (1.0 - std::exp(-kK * exit_distance(x, d, lo, hi)));
        }
    }
    return sum * 4.0 * M_PI / (double(n_z) * n_phi);
}

/// Mean of exp(-K r) / r^2 over the cube [lo, lo + edge]^3, r the distance from `x` (outside it):
/// a midpoint rule on 40^3 points.
double mean_attenuated_inverse_square(const glm::dvec3& x, const glm::dvec3& lo, double edge) {
    const int n = 40;
    double sum = 0.0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k) {
                const glm::dvec3 p = lo + edge * (glm::dvec3(i, j, k) + 0.5) / double(n);
                const double r = glm::length(p - x);
                sum += std::exp(-kK * r) / (r * r);
            }
    return sum / (double(n) * n * n);
}

/// The zone holding `x` (inside a zone, not on its boundary).
std::size_t zone_at(const Zones& zones, const Vec3& x) {
    for (std::size_t k = 0; k < zones.size(); ++k)
        if (glm::all(glm::lessThan(glm::abs(zones.centre[k] - x), Vec3(0.5f * zones.edge[k])))) return k;
    ADD_FAILURE() << "no zone holds " << x.x << " " << x.y << " " << x.z;
    return 0;
}

PointLight lamp(double intensity) {
    PointLight l;
    l.position = kLamp;
    l.intensity = Rgb(intensity);
    return l;
}

}  // namespace

/// No surfaces: the zones take up what the fog cube extinguishes, in total, in the zone that holds
/// the lamp (taken from directions) and in a zone far from it (taken at points).
TEST(LampsInMedia, AFogCubeTakesUpWhatItExtinguishes) {
    const std::vector<Medium> media{fog_cube(0.5)};
    const Zones zones = build_zones(media);
    Lights lights;
    lights.points.push_back(lamp(3.0));
    const LampsThroughMedia lit = lamps_through_media(Elements{}, lights, zones, MediumTracer(media, zones));
    ASSERT_EQ(lit.zone_incident.size(), zones.size());

    // P_k = 4 pi K_t V H_k; their sum is what the cube takes up of the lamp's 4 pi I.
    double taken = 0.0;
    for (std::size_t k = 0; k < zones.size(); ++k) taken += 4.0 * M_PI * kK * zones.volume(k) * lit.zone_incident[k].g;
    const glm::dvec3 x(kLamp);
    EXPECT_NEAR(taken / (3.0 * taken_up_over_directions(x, glm::dvec3(0.0), glm::dvec3(2.0))), 1.0, 0.005);

    const std::size_t own = zone_at(zones, kLamp);
    const glm::dvec3 own_lo = glm::dvec3(zones.centre[own]) - 0.0625;
    const double own_taken = taken_up_over_directions(x, own_lo, own_lo + 0.125);
    EXPECT_NEAR(lit.zone_incident[own].r / (3.0 * own_taken / (4.0 * M_PI * kK * zones.volume(own))), 1.0, 0.001);

    const std::size_t far = zone_at(zones, Vec3(1.7f, 0.2f, 1.45f));
    const glm::dvec3 far_lo = glm::dvec3(zones.centre[far]) - 0.0625;
    const double far_mean = mean_attenuated_inverse_square(x, far_lo, 0.125);
    EXPECT_NEAR(lit.zone_incident[far].b / (3.0 * far_mean / (4.0 * M_PI)), 1.0, 0.005);
}

/// A spot of 60 degrees with a soft edge, pointing down and sideways: the fog takes up what its
/// profile sends, Cycles' smoothstep times the cosine to its axis.
TEST(LampsInMedia, AFogCubeTakesUpWhatASpotSends) {
    const std::vector<Medium> media{fog_cube(0.5)};
    const Zones zones = build_zones(media);
    PointLight spot = lamp(1.0);
    spot.direction = glm::normalize(Vec3(0.3f, 0.2f, -1.0f));
    spot.cos_half_angle = float(std::cos(M_PI / 6.0));
    spot.smooth = 0.4f * (1.0f - spot.cos_half_angle);
    Lights lights;
    lights.points.push_back(spot);
    const LampsThroughMedia lit = lamps_through_media(Elements{}, lights, zones, MediumTracer(media, zones));
    double taken = 0.0;
    for (std::size_t k = 0; k < zones.size(); ++k) taken += 4.0 * M_PI * kK * zones.volume(k) * lit.zone_incident[k].g;
    const auto profile = [&](const glm::dvec3& d) {  // written out from Cycles' spot_attenuation
        const double c = glm::dot(d, glm::dvec3(spot.direction)), t = c - spot.cos_half_angle;
        if (t <= 0.0) return 0.0;
        const double s = std::min(1.0, t / spot.smooth);
        return c * s * s * (3.0 - 2.0 * s);
    };
    EXPECT_NEAR(taken / taken_up_over_directions(glm::dvec3(kLamp), glm::dvec3(0.0), glm::dvec3(2.0), profile), 1.0,
                0.005);
}

/// A lamp of radius 0.1 m is, as in Cycles 3.x, a disk facing each point with radiance
/// I / (pi r^2): its light in the fog is bounded, 2 I / r^2 (1 - d / sqrt(d^2 + r^2)), and the zone
/// that holds it takes the mean of that, exp(-K d) along the way.
TEST(LampsInMedia, TheZoneAroundALampWithARadiusTakesItsDisksLight) {
    const std::vector<Medium> media{fog_cube(0.5)};
    const Zones zones = build_zones(media);
    PointLight disk = lamp(1.0);
    disk.radius = 0.1f;
    Lights lights;
    lights.points.push_back(disk);
    const LampsThroughMedia lit = lamps_through_media(Elements{}, lights, zones, MediumTracer(media, zones));
    for (const Vec3& at : {kLamp, Vec3(1.2f, 1.1f, 0.8f)}) {
        const std::size_t k = zone_at(zones, at);
        const int n = 40;
        double sum = 0.0;
        for (int i = 0; i < n * n * n; ++i) {
            const glm::dvec3 cell(i % n, (i / n) % n, i / (n * n));
            const glm::dvec3 x = glm::dvec3(zones.centre[k]) + 0.125 * ((cell + 0.5) / double(n) - 0.5);
            const double d = glm::length(x - glm::dvec3(kLamp)), r = 0.1;
            sum += std::exp(-kK * d) * 2.0 / (r * r) * (1.0 - d / std::sqrt(d * d + r * r));
        }
        EXPECT_NEAR(lit.zone_incident[k].g / (sum / (n * n * n) / (4.0 * M_PI)), 1.0, 0.005) << "zone " << k;
    }
}

/// A sun of irradiance E shining through the top of the fog cube at 30 degrees: a zone whose rays
/// towards the sun leave through the top takes E / (4 pi) times the mean over its height of
/// exp(-K (2 - z) / cos 30), in closed form.
TEST(LampsInMedia, TheSunLightsTheFogAsItsDepthTowardsTheSunSays) {
    const std::vector<Medium> media{fog_cube(0.5)};
    const Zones zones = build_zones(media);
    const double tilt = M_PI / 6.0;
    SunLight sun;
    sun.direction = Vec3(float(std::sin(tilt)), 0.0f, float(-std::cos(tilt)));
    sun.irradiance = Rgb(2.0);
    Lights lights;
    lights.suns.push_back(sun);
    const LampsThroughMedia lit = lamps_through_media(Elements{}, lights, zones, MediumTracer(media, zones));
    for (const Vec3& at : {Vec3(1.45f, 1.02f, 1.9f), Vec3(1.8f, 0.3f, 1.3f), Vec3(1.9f, 1.7f, 1.6f)}) {
        const std::size_t k = zone_at(zones, at);
        const double z0 = zones.centre[k].z - 0.0625, z1 = z0 + 0.125, a = kK / std::cos(tilt);
        const double mean = (std::exp(-a * (2.0 - z1)) - std::exp(-a * (2.0 - z0))) / (a * 0.125);
        EXPECT_NEAR(lit.zone_incident[k].r / (2.0 * mean / (4.0 * M_PI)), 1.0, 1e-3) << "zone " << k;
    }
}

/// The walls of a closed box around the fog take the lamp's light dimmed by exp(-K r) along the way.
TEST(LampsInMedia, WallsSeeTheLampThroughTheFog) {
    const test::SceneArrays scene = test::closed_box(Vec3(2.0f), Rgb(0.5), Rgb(0.0));
    const Elements elements = build_elements(scene.input(), 0.25f).elements;
    const std::vector<Medium> media{fog_cube(0.5)};
    const Zones zones = build_zones(media);
    Lights lights;
    lights.points.push_back(lamp(1.0));
    const LampsThroughMedia lit = lamps_through_media(elements, lights, zones, MediumTracer(media, zones));
    const std::vector<Rgb> clear = direct_irradiance(elements, lights);
    for (std::size_t e = 0; e < elements.size(); ++e) {
        const double r = glm::length(elements.centre[e] - kLamp);
        EXPECT_NEAR(lit.element_irradiance[e].g / clear[e].g, std::exp(-kK * r), 1e-4) << "element " << e;
    }
}

/// A closed box whose walls reflect rho and whose fog scatters Omega = rho: all of the lamp's
/// 4 pi I is absorbed, (1 - rho) of all the light that arrives anywhere, so the light leaving the
/// walls and the fog, pi (sum A L + sum 4 K_t V L_k), is rho / (1 - rho) of it.
TEST(LampsInMedia, AClosedFoggyBoxReflectsRhoOverOneMinusRhoOfTheLamp) {
    const double rho = 0.6;
    const test::SceneArrays scene = test::closed_box(Vec3(2.0f), Rgb(rho), Rgb(0.0));
    BakeSettings settings;
    settings.element_size = 0.25f;
    settings.resolution = 64;
    settings.solve.tolerance = 1e-6;
    settings.lights.points.push_back(lamp(2.0));
    const std::vector<Medium> media{fog_cube(rho)};
    const ZonalBakeResult r = bake_with_media(scene.input(), media, settings, 16);
    ASSERT_TRUE(r.surfaces.solve.converged);
    const Elements& e = r.surfaces.build.elements;
    double leaving = 0.0;
    for (std::size_t i = 0; i < e.size(); ++i) leaving += M_PI * e.area[i] * r.surfaces.solve.radiance[i].g;
    for (std::size_t k = 0; k < r.zones.size(); ++k) leaving += M_PI * r.zones.weight(k).g * r.zone_radiance[k].g;
    EXPECT_NEAR(leaving / (rho / (1.0 - rho) * 4.0 * M_PI * 2.0), 1.0, 0.005);
}
