/// @file test_zonal_merge.cpp
/// @brief Zones merged into uniform octree blocks: which blocks merge (counted on a constructed
/// grid); the ray walk through a merged zone credits what its voxels would; a uniform medium
/// merged into blocks bakes exactly as a coarser grid of the same medium, and within the measured
/// discretisation difference of the unmerged bake; isothermal enclosures stay exact; a merged
/// block's radiance comes back onto its voxels linear in space with its power kept.
#include "bake/media_bake.h"
#include "media/zonal_solver.h"
#include "testing/test_util.h"

#include <gtest/gtest.h>
#include <glm/common.hpp>

#include <cmath>
#include <map>

using namespace radiosity;

namespace {

Medium uniform_cube(int n, const Rgb& K, const Rgb& albedo) {
    Medium m(Vec3(0.0f), 1.0f / n, {n, n, n});
    for (std::size_t v = 0; v < m.voxel_count(); ++v) {
        m.extinction[v] = K;
        m.albedo[v] = albedo;
    }
    return m;
}

/// 6 x 4 x 4 voxels: x < 4 uniform but for voxel (1, 1, 1), which emits; x >= 4 uniform where z >= 2,
/// varying per voxel where z < 2, with voxel (5, 0, 0) empty.
Medium constructed_grid() {
    Medium m(Vec3(0.5f, 0.0f, 0.0f), 0.1f, {6, 4, 4});
    for (int32_t z = 0; z < 4; ++z)
        for (int32_t y = 0; y < 4; ++y)
            for (int32_t x = 0; x < 6; ++x) {
                const std::size_t v = m.index(x, y, z);
                m.extinction[v] = x < 4 ? Rgb(2.0, 1.0, 3.0) : z >= 2 ? Rgb(1.0) : Rgb(1.0 + 0.1 * double(v));
                m.albedo[v] = Rgb(0.5);
            }
    m.emission[m.index(1, 1, 1)] = Rgb(0.3);
    m.extinction[m.index(5, 0, 0)] = Rgb(0.0);
    // Float rounding of a voxelised density: within kUniformTolerance, still uniform.
    m.extinction[m.index(3, 3, 3)] *= 1.0 + 1e-6;
    return m;
}

}  // namespace

TEST(ZoneMerging, OnlyUniformAlignedBlocksInsideTheGridMerge) {
    const std::vector<Medium> media{constructed_grid()};
    const Zones voxels = build_zones(media);
    ASSERT_EQ(voxels.size(), 95u);  // 96 voxels, one empty
    for (std::size_t k = 0; k < voxels.size(); ++k) EXPECT_EQ(voxels.block[k], 1);

    const Zones zones = build_zones(media, 2);
    // Block (0..3)^3: voxel (1, 1, 1) differs, so its 2^3 child splits into 8 voxels and the other
    // 7 children merge (15). Block at x = 4 would leave the grid: of its 4 children of 2^3, the two
    // at z >= 2 merge, the two at z < 2 vary (8 + 7 voxels): 17. Total 32.
    ASSERT_EQ(zones.size(), 32u);
    std::map<int32_t, int> by_block;
    std::size_t covered = 0;
    for (std::size_t k = 0; k < zones.size(); ++k) {
        ++by_block[zones.block[k]];
        covered += std::size_t(zones.block[k]) * zones.block[k] * zones.block[k];
    }
    EXPECT_EQ(by_block[2], 9);
    EXPECT_EQ(by_block[1], 23);
    EXPECT_EQ(covered, 95u);
    // The merged block at voxel (2, 2, 2): its centre, edge, weight 4 K V and mean extinction.
    const Medium& m = media[0];
    for (std::size_t k = 0; k < zones.size(); ++k) {
        if (zones.voxel[k] != int32_t(m.index(2, 2, 2))) continue;
        EXPECT_EQ(zones.block[k], 2);
        EXPECT_NEAR(zones.centre[k].x, 0.5f + 0.3f, 1e-6f);
        EXPECT_NEAR(zones.centre[k].y, 0.3f, 1e-6f);
        EXPECT_NEAR(zones.edge[k], 0.2f, 1e-7f);
        EXPECT_NEAR(zones.extinction[k].b, 3.0 * (1.0 + 1e-6 / 8), 1e-12);
        EXPECT_NEAR(zones.weight(k).r / (4.0 * 2.0 * (1.0 + 1e-6 / 8) * 0.008), 1.0, 1e-7);  // float edge
        EXPECT_EQ(zones.albedo[k], Rgb(0.5));
    }
    // Every voxel maps to the zone holding it.
    const std::vector<int32_t> zone_of = voxel_zones(m, 0, zones);
    EXPECT_EQ(zone_of[m.index(5, 0, 0)], -1);
    EXPECT_EQ(zone_of[m.index(3, 3, 3)], zone_of[m.index(2, 2, 2)]);
    EXPECT_NE(zone_of[m.index(1, 1, 1)], zone_of[m.index(0, 0, 0)]);
}

TEST(ZoneMerging, RayWalkCreditsAMergedZoneWhatItsVoxelsTake) {
    const std::vector<Medium> media{uniform_cube(8, Rgb(0.7, 2.0, 5.0), Rgb(0.5))};
    const Zones voxels = build_zones(media), blocks = build_zones(media, 2);
    ASSERT_EQ(blocks.size(), 8u);
    const MediumTracer fine(media, voxels), merged(media, blocks);
    const std::vector<int32_t> block_of = voxel_zones(media[0], 0, blocks);
    std::vector<ZoneCredit> fine_credits, merged_credits;
    for (int ray = 0; ray < 50; ++ray) {
        const double u = std::fmod(0.618034 * ray, 1.0), w = std::fmod(0.754878 * ray, 1.0);
        const double z = 2.0 * u - 1.0, phi = 2.0 * M_PI * w, r = std::sqrt(1.0 - z * z);
        const Vec3 d(r * std::cos(phi), r * std::sin(phi), z);
        const Vec3 origin(0.5f + 0.3f * float(u), 0.4f, 0.45f + 0.1f * float(w));
        const Channels tau_fine = fine.trace(origin, d, 0.8f, fine_credits);
        const Channels tau_merged = merged.trace(origin, d, 0.8f, merged_credits);
        std::vector<Channels> expected(blocks.size(), Channels(0.0f)), got(blocks.size(), Channels(0.0f));
        for (const ZoneCredit& c : fine_credits) expected[block_of[voxels.voxel[c.zone]]] += c.fraction;
        for (const ZoneCredit& c : merged_credits) got[c.zone] += c.fraction;
        EXPECT_LE(merged_credits.size(), 8u);  // one credit per zone crossed
        for (int ch = 0; ch < 3; ++ch) {
            EXPECT_NEAR(tau_merged[ch], tau_fine[ch], 1e-6f) << "ray " << ray;
            for (std::size_t k = 0; k < blocks.size(); ++k)
                EXPECT_NEAR(got[k][ch], expected[k][ch], 1e-6f) << "ray " << ray;
        }
    }
}

namespace {

/// 8^3 voxels in the unit cube: x < 3 one medium, x >= 3 another (RGB), so that blocks of 4, 2
/// and single voxels meet at the seam (level 2: 4 blocks of 4^3, 16 of 2^3, 128 voxels).
Medium two_media_with_a_seam(const Rgb& L0) {
    Medium m(Vec3(0.0f), 0.125f, {8, 8, 8});
    for (int32_t z = 0; z < 8; ++z)
        for (int32_t y = 0; y < 8; ++y)
            for (int32_t x = 0; x < 8; ++x) {
                const std::size_t v = m.index(x, y, z);
                const bool left = x < 3;
                m.extinction[v] = left ? Rgb(2.0, 4.0, 1.0) : Rgb(6.0, 3.0, 0.5);
                m.albedo[v] = left ? Rgb(0.3, 0.6, 0.9) : Rgb(0.8, 0.1, 0.5);
                m.emission[v] = m.extinction[v] * (1.0 - m.albedo[v]) * L0;  // K_a L0: Kirchhoff
            }
    return m;
}

Rgb linear(const glm::dvec3& p) {
    return Rgb(3.0 + 0.5 * p.x - 0.7 * p.y + 0.9 * p.z, 2.0 - 0.3 * p.x, 1.5 + 0.2 * p.z);
}

}  // namespace

TEST(ZoneMerging, IsothermalEnclosureStaysExact) {
    const Rgb L0(1.0, 2.0, 0.5), rho(0.5, 0.3, 0.7);
    const test::SceneArrays box = test::closed_box(Vec3(1.0f), rho, (1.0 - rho) * L0);
    const Elements elements = build_elements(box.input(), 0.25f).elements;
    const std::vector<Medium> media{two_media_with_a_seam(L0)};
    const Zones zones = build_zones(media, 2);
    ASSERT_EQ(zones.size(), 4u + 16u + 128u);
    ZonalFactorSettings settings;
    settings.surface_resolution = 32;
    settings.zone_resolution = 16;
    ZonalMatrix R = compute_exchange_factors(elements, media, zones, settings);
    // Rows and unknowns of the walls' back sides (the walls emit: two-sided) face out of the box.
    auto back = [&](std::size_t x) { return x < elements.size() && elements.is_back(x); };
    for (std::size_t x = 0; x < R.rows(); ++x) {
        if (back(x)) continue;
        Rgb sum(0.0);
        for (int64_t k = R.row_start[x]; k < R.row_start[x + 1]; ++k) sum += R.value(k);
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(sum[c], 1.0, 2e-5) << "row " << x;
    }
    enforce_reciprocity(R, zonal_weights(elements, zones));
    SolveSettings solve;
    solve.tolerance = 1e-7;
    for (Method method : {Method::GaussSeidel, Method::Progressive}) {
        solve.method = method;
        const SolveResult r = solve_zonal(elements, zones, R, solve);
        ASSERT_TRUE(r.converged);
        for (std::size_t x = 0; x < r.radiance.size(); ++x)
            for (int c = 0; c < 3; ++c)
                if (!back(x)) ASSERT_NEAR(r.radiance[x][c] / L0[c], 1.0, 1e-5) << "unknown " << x;
    }
}

TEST(ZoneMerging, MergedBlocksComeBackLinearWithTheirPowerKept) {
    const std::vector<Medium> media{two_media_with_a_seam(Rgb(1.0))};
    const Medium& m = media[0];
    const Zones zones = build_zones(media, 2);
    std::vector<Rgb> L(zones.size());
    for (std::size_t k = 0; k < zones.size(); ++k) L[k] = linear(glm::dvec3(zones.centre[k]));
    const std::vector<Rgb> voxel = voxel_radiance(m, 0, zones, L);
    for (int32_t z = 0; z < 8; ++z)
        for (int32_t y = 0; y < 8; ++y)
            for (int32_t x = 0; x < 8; ++x) {
                const Rgb exact = linear(glm::dvec3(m.origin) + 0.125 * glm::dvec3(x + 0.5, y + 0.5, z + 0.5));
                for (int c = 0; c < 3; ++c)
                    ASSERT_NEAR(voxel[m.index(x, y, z)][c], exact[c], 1e-6) << x << " " << y << " " << z;
            }
    // A field that falls steeply, clamped at 0 in places: each block's mean is still its L_k.
    for (std::size_t k = 0; k < zones.size(); ++k)
        L[k] = Rgb(std::exp(-8.0 * zones.centre[k].z), 0.2 - zones.centre[k].x, 1.0);
    for (Rgb& l : L) l = glm::max(l, Rgb(0.0));
    const std::vector<Rgb> kept = voxel_radiance(m, 0, zones, L);
    std::vector<Rgb> sum(zones.size(), Rgb(0.0));
    const std::vector<int32_t> zone_of = voxel_zones(m, 0, zones);
    for (std::size_t v = 0; v < m.voxel_count(); ++v) sum[zone_of[v]] += kept[v];
    for (std::size_t k = 0; k < zones.size(); ++k) {
        const double n = double(zones.block[k]) * zones.block[k] * zones.block[k];
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[k][c] / n, L[k][c], 1e-12) << "zone " << k;
    }
}

namespace {

/// The closed unit box (walls rho 0.5, the ceiling glowing 4) full of uniform grey fog, K_t = 3 / m,
/// albedo 0.8, on n^3 voxels merged up to max_block_level.
ZonalBakeResult fog_box(int n, int max_block_level) {
    test::SceneArrays scene = test::closed_box(Vec3(1.0f), Rgb(0.5), Rgb(0.0));
    scene.emission[3] = scene.emission[4] = scene.emission[5] = 4.0f;  // polygon 1: the ceiling
    BakeSettings settings;
    settings.element_size = 0.25f;
    settings.resolution = 32;
    settings.solve.tolerance = 1e-7;
    return bake_with_media(scene.input(), {uniform_cube(n, Rgb(3.0), Rgb(0.8))}, settings, 16, {}, 1, max_block_level);
}

double worst_relative(const std::vector<Rgb>& a, const std::vector<Rgb>& b) {
    double worst = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i].r / b[i].r - 1.0));
    return worst;
}

}  // namespace

/// 8^3 voxels merged into 2^3 blocks are the 4^3 grid's zones: same centres, edges, coefficients and
/// ray start points, and the walk through the finer voxels gives the same transmittance.
TEST(ZoneMerging, UniformFogMergedBakesAsTheCoarserGrid) {
    const ZonalBakeResult merged = fog_box(8, 1), coarse = fog_box(4, 0);
    ASSERT_EQ(merged.zones.size(), 64u);
    ASSERT_EQ(coarse.zones.size(), 64u);
    EXPECT_LT(worst_relative(merged.zone_radiance, coarse.zone_radiance), 1e-5);
    EXPECT_LT(worst_relative(merged.surfaces.solve.radiance, coarse.surfaces.solve.radiance), 1e-5);
}

TEST(ZoneMerging, UniformFogMergedAgreesWithTheUnmergedBake) {
    const ZonalBakeResult merged = fog_box(8, 1), fine = fog_box(8, 0);
    ASSERT_EQ(fine.zones.size(), 512u);
    // Each merged zone against the mean of the 8 voxels it replaces.
    const std::vector<int32_t> block_of = voxel_zones(uniform_cube(8, Rgb(3.0), Rgb(0.8)), 0, merged.zones);
    std::vector<Rgb> fine_mean(merged.zones.size(), Rgb(0.0));
    for (std::size_t k = 0; k < fine.zones.size(); ++k)
        fine_mean[block_of[fine.zones.voxel[k]]] += fine.zone_radiance[k] / 8.0;
    // The merged bake is the 4^3 grid's (test above), so they differ by the discretisation
    // difference between 4^3 and 8^3 zones. Measured: zones 11.2%, walls 16.5% at worst (the dark
    // floor corners), 1.9% in the area-weighted mean; against a 16^3 bake the 4^3 and 8^3 walls are
    // 2.35% and 0.61% off in the mean (second order: 4x per halving), so this is the coarse grid's
    // error, not a fault of merging.
    EXPECT_LT(worst_relative(merged.zone_radiance, fine_mean), 0.115);
    const std::vector<Rgb>& L = merged.surfaces.solve.radiance;
    const std::vector<Rgb>& L_fine = fine.surfaces.solve.radiance;
    EXPECT_LT(worst_relative(L, L_fine), 0.17);
    const std::vector<float>& area = fine.surfaces.build.elements.area;
    double difference = 0.0, total = 0.0;
    for (std::size_t i = 0; i < L.size(); ++i) {
        difference += area[i] * std::abs(L[i].r - L_fine[i].r);
        total += area[i] * L_fine[i].r;
    }
    EXPECT_LT(difference / total, 0.02);
}
