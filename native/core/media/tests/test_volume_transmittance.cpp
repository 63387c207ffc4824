/// @file test_volume_transmittance.cpp
/// @brief Media, zones and the transmittance walk against closed forms: slabs at several angles,
/// layered slabs, partial voxels, rays along voxel boundaries, several media; Cycles' coefficients.
#include "media/transmittance.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <cmath>

using namespace radiosity;

namespace {

/// A slab z in [0, thickness] of wide extent, `layers` voxel layers, K_t per layer from `K`.
Medium slab(int layers, float voxel, const std::vector<Rgb>& K) {
    Medium m(Vec3(0.0f), voxel, {64, 64, layers});
    for (int z = 0; z < layers; ++z)
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) m.extinction[m.index(x, y, z)] = K[z % K.size()];
    return m;
}

Channels credited(const std::vector<ZoneCredit>& credits) {
    Channels sum(0.0f);
    for (const ZoneCredit& c : credits) sum += c.fraction;
    return sum;
}

void expect_closed(const Channels& tau, const std::vector<ZoneCredit>& credits) {
    const Channels total = tau + credited(credits);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(total[c], 1.0f, 2e-6f);
}

}  // namespace

TEST(Transmittance, HomogeneousSlabAtSeveralAngles) {
    const Rgb K(0.7, 1.3, 2.0);
    const std::vector<Medium> media{slab(4, 0.25f, {K})};  // 1 m thick, 16 m wide
    const Zones zones = build_zones(media);
    const MediumTracer tracer(media, zones);
    std::vector<ZoneCredit> credits;
    for (double degrees : {0.0, 10.0, 30.0, 45.0, 60.0, 75.0}) {
        for (double azimuth : {0.0, 0.3, 1.9}) {
            const double theta = degrees * M_PI / 180.0;
            const Vec3 d(std::sin(theta) * std::cos(azimuth), std::sin(theta) * std::sin(azimuth), std::cos(theta));
            const Vec3 origin(8.03f, 7.91f, -0.5f);
            const Channels tau = tracer.trace(origin, d, INFINITY, credits);
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(tau[c], std::exp(-K[c] / std::cos(theta)), 2e-6 + 2e-5 * std::exp(-K[c] / std::cos(theta)))
                    << degrees << " degrees, channel " << c;
            expect_closed(tau, credits);
        }
    }
}

TEST(Transmittance, LayeredSlabCreditsEachLayerWhatItRemoves) {
    const std::vector<Rgb> K{Rgb(0.5), Rgb(3.0), Rgb(0.0), Rgb(1.5)};  // a gap: not zones
    const std::vector<Medium> media{slab(4, 0.5f, K)};
    const Zones zones = build_zones(media);
    EXPECT_EQ(zones.size(), 64u * 64u * 3u);
    const MediumTracer tracer(media, zones);
    std::vector<ZoneCredit> credits;
    const double theta = 0.6, cos_theta = std::cos(theta);
    const Vec3 d(std::sin(theta), 0.0f, cos_theta);
    const Channels tau = tracer.trace(Vec3(3.1f, 5.2f, -1.0f), d, INFINITY, credits);
    // Per layer: tau before it times (1 - exp(-K s)), s = 0.5 / cos.
    double before = 1.0;
    std::vector<double> layer_credit(4, 0.0);
    std::vector<double> expected(4);
    for (int z = 0; z < 4; ++z) {
        const double after = before * std::exp(-K[z].r * 0.5 / cos_theta);
        expected[z] = before - after;
        before = after;
    }
    for (const ZoneCredit& c : credits) layer_credit[zones.voxel[c.zone] / (64 * 64)] += c.fraction.r;
    for (int z = 0; z < 4; ++z) EXPECT_NEAR(layer_credit[z], expected[z], 1e-5) << "layer " << z;
    EXPECT_NEAR(tau.r, before, 1e-6);
    expect_closed(tau, credits);
}

TEST(Transmittance, PartialPathsInsideVoxels) {
    const std::vector<Medium> media{slab(4, 0.25f, {Rgb(2.0)})};
    const MediumTracer tracer(media, build_zones(media));
    std::vector<ZoneCredit> credits;
    // Starts inside a voxel, ends inside another: only the path inside counts.
    const Vec3 d = glm::normalize(Vec3(0.3f, -0.2f, 1.0f));
    const float t_max = 0.61f;
    const Channels tau = tracer.trace(Vec3(4.1f, 4.2f, 0.13f), d, t_max, credits);
    const double inside = std::min<double>(t_max, (1.0 - 0.13) / d.z);
    EXPECT_NEAR(tau.r, std::exp(-2.0 * inside), 1e-6);
    expect_closed(tau, credits);
}

TEST(Transmittance, RaysAlongVoxelBoundariesAndAxes) {
    const std::vector<Medium> media{slab(4, 0.25f, {Rgb(1.0)})};
    const MediumTracer tracer(media, build_zones(media));
    std::vector<ZoneCredit> credits;
    // Along +x inside the slab on a voxel boundary plane y = 2, z = 0.5: 16 m of medium minus the start.
    const Channels along = tracer.trace(Vec3(1.0f, 2.0f, 0.5f), Vec3(1, 0, 0), 3.0f, credits);
    EXPECT_NEAR(along.r, std::exp(-3.0), 1e-6);
    expect_closed(along, credits);
    // Straight down from exactly on the top face.
    const Channels down = tracer.trace(Vec3(2.0f, 2.0f, 1.0f), Vec3(0, 0, -1), INFINITY, credits);
    EXPECT_NEAR(down.r, std::exp(-1.0), 1e-6);
    expect_closed(down, credits);
    // Parallel to the slab, outside it: untouched.
    EXPECT_EQ(tracer.trace(Vec3(2.0f, 2.0f, 1.5f), Vec3(1, 0, 0), INFINITY, credits), Channels(1.0f));
    EXPECT_TRUE(credits.empty());
}

TEST(Transmittance, SeveralMediaInRayOrder) {
    Medium near(Vec3(0.0f, 0.0f, 1.0f), 0.5f, {2, 2, 2});
    Medium far(Vec3(0.0f, 0.0f, 3.0f), 0.25f, {4, 4, 4});
    for (Rgb& K : near.extinction) K = Rgb(1.0);
    for (Rgb& K : far.extinction) K = Rgb(0.5);
    const std::vector<Medium> media{far, near};  // listed out of ray order on purpose
    const Zones zones = build_zones(media);
    const MediumTracer tracer(media, zones);
    std::vector<ZoneCredit> credits;
    const Channels tau = tracer.trace(Vec3(0.4f, 0.6f, 0.0f), Vec3(0, 0, 1), INFINITY, credits);
    EXPECT_NEAR(tau.r, std::exp(-1.0 - 0.5), 1e-6);
    ASSERT_FALSE(credits.empty());
    EXPECT_EQ(zones.medium[credits.front().zone], 1);  // the near medium is met first
    EXPECT_NEAR(credits.front().fraction.r, 1.0 - std::exp(-0.5), 1e-6);
    expect_closed(tau, credits);
}

TEST(Zones, OnlyVoxelsWithExtinctionAreZones) {
    Medium m(Vec3(0.0f), 0.1f, {64, 64, 64});
    for (int z = 10; z < 14; ++z)
        for (int y = 20; y < 24; ++y)
            for (int x = 30; x < 34; ++x) {
                m.extinction[m.index(x, y, z)] = Rgb(2.0, 4.0, 0.5);
                m.emission[m.index(x, y, z)] = Rgb(1.0, 1.0, 1.0);
            }
    const Zones zones = build_zones({m});
    ASSERT_EQ(zones.size(), 64u);                      // of 262144 voxels
    EXPECT_EQ(zones.emitted[0], Rgb(0.5, 0.25, 2.0));  // emission / K_t
    EXPECT_NEAR(zones.centre[0].x, 3.05f, 1e-6f);
    const double h = 0.1f;  // the voxel edge as stored (float)
    EXPECT_NEAR(zones.weight(0).g, 4.0 * 4.0 * h * h * h, 1e-15);
}

TEST(Zones, RejectsWhatTheZonalSystemCannotHold) {
    Medium m(Vec3(0.0f), 1.0f, {2, 1, 1});
    m.emission[1] = Rgb(1.0);  // emits but never absorbs
    EXPECT_THROW(build_zones({m}), InputError);
    m.emission[1] = Rgb(0.0);
    m.extinction[0] = Rgb(1.0);
    m.albedo[0] = Rgb(1.5);
    EXPECT_THROW(build_zones({m}), InputError);
    m.albedo[0] = Rgb(0.5);
    EXPECT_NO_THROW(build_zones({m}));
    Medium other(Vec3(0.5f, 0.0f, 0.0f), 1.0f, {1, 1, 1});
    other.extinction[0] = Rgb(1.0);
    EXPECT_THROW(build_zones({m, other}), InputError);  // occupied boxes overlap
    other.origin = Vec3(1.0f, 0.0f, 0.0f);              // touching is fine
    EXPECT_NO_THROW(build_zones({m, other}));
}

TEST(PrincipledVolume, MatchesCyclesClosure) {
    const VolumeCoefficients c =
        principled_volume(Rgb(0.8, 0.5, 0.2), 2.0, Rgb(0.25, 1.0, 0.0), 3.0, Rgb(1.0, 0.5, 0.0));
    // sqrt(absorption colour) = (0.5, 1, 0); 1 - colour = (0.2, 0.5, 0.8).
    EXPECT_NEAR(c.scattering.r, 1.6, 1e-12);
    EXPECT_NEAR(c.scattering.b, 0.4, 1e-12);
    EXPECT_NEAR(c.absorption.r, 2.0 * 0.2 * 0.5, 1e-12);
    EXPECT_NEAR(c.absorption.g, 0.0, 1e-12);
    EXPECT_NEAR(c.absorption.b, 2.0 * 0.8 * 1.0, 1e-12);
    EXPECT_EQ(c.emission, Rgb(3.0, 1.5, 0.0));
    // Colour above 1 absorbs nothing (max(1 - colour, 0)); negative density is none.
    EXPECT_EQ(principled_volume(Rgb(1.5), 1.0, Rgb(0.0), 0.0, Rgb(0.0)).absorption, Rgb(0.0));
    EXPECT_EQ(principled_volume(Rgb(0.5), -1.0, Rgb(0.0), 0.0, Rgb(0.0)).extinction(), Rgb(0.0));

    Medium m(Vec3(0.0f), 1.0f, {1, 1, 1});
    m.set(0, c);
    EXPECT_NEAR(m.albedo[0].r, 1.6 / 1.8, 1e-12);
    EXPECT_NEAR(m.albedo[0].g, 1.0, 1e-12);
}
