/// @file test_zonal_grids.cpp
/// @brief medium_grids(): a radiance linear in space comes back exactly at the fine cells' centres
/// (interior and, where the medium is two zones thick, border); every zone's emitted power
/// (sum of emission * volume) is kept; subdivision 1 is K_t and K_t L per zone.
#include "media/zonal_grids.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace radiosity;

namespace {

/// A 6 x 6 x 7 grid of 0.2 m voxels at (1, -1, 0.5), every voxel a zone of extinction
/// varying per voxel and channel, but `holes` empty.
Medium medium_with_holes(const std::vector<std::array<int32_t, 3>>& holes) {
    Medium m(Vec3(1.0f, -1.0f, 0.5f), 0.2f, {6, 6, 7});
    for (std::size_t v = 0; v < m.voxel_count(); ++v)
        m.extinction[v] = Rgb(1.0 + 0.1 * (v % 7), 2.0, 0.5 + 0.05 * (v % 3));
    for (const auto& h : holes) m.extinction[m.index(h[0], h[1], h[2])] = Rgb(0.0);
    return m;
}

/// Independent truth: a field linear in world space, different per channel, positive over the grid.
Rgb linear(const glm::dvec3& p) {
    return Rgb(3.0 + 0.5 * p.x - 0.7 * p.y + 0.9 * p.z, 2.0 - 0.3 * p.x + 0.2 * p.y - 0.4 * p.z, 1.5 + 0.1 * p.x);
}

/// Centre of cell (x, y, z) of edge `voxel` / `s` (the medium's edge: g.voxel_size is rounded to float).
glm::dvec3 centre(const Vec3& origin, float voxel, int32_t x, int32_t y, int32_t z, int s = 1) {
    return glm::dvec3(origin) + double(voxel) / s * glm::dvec3(x + 0.5, y + 0.5, z + 0.5);
}

/// The medium's zones at their centres' linear values (0 elsewhere).
std::vector<Rgb> linear_radiance(const Medium& m) {
    std::vector<Rgb> L(m.voxel_count(), Rgb(0.0));
    for (int32_t z = 0; z < m.dims[2]; ++z)
        for (int32_t y = 0; y < m.dims[1]; ++y)
            for (int32_t x = 0; x < m.dims[0]; ++x)
                L[m.index(x, y, z)] = linear(centre(m.origin, m.voxel_size, x, y, z));
    return L;
}

bool zone(const Medium& m, int32_t x, int32_t y, int32_t z) {
    const Rgb& K = m.extinction[m.index(x, y, z)];
    return K.r > 0.0 || K.g > 0.0 || K.b > 0.0;
}

/// Checks every fine cell of `g` (subdivision s) against the linear field, K_t against the zone's.
void expect_linear_reproduced(const Medium& m, const MediumGrids& g, int s) {
    int checked = 0;
    for (int32_t z = 0; z < g.dims[2]; ++z)
        for (int32_t y = 0; y < g.dims[1]; ++y)
            for (int32_t x = 0; x < g.dims[0]; ++x) {
                const std::size_t f = x + std::size_t(g.dims[0]) * (y + std::size_t(g.dims[1]) * z);
                const Rgb K = m.extinction[m.index(x / s, y / s, z / s)];
                ASSERT_EQ(g.density[f], K);
                if (!zone(m, x / s, y / s, z / s)) {
                    ASSERT_EQ(g.emission[f], Rgb(0.0));
                    continue;
                }
                const Rgb expected = K * linear(centre(m.origin, m.voxel_size, x, y, z, s));
                for (int ch = 0; ch < 3; ++ch)
                    ASSERT_NEAR(g.emission[f][ch], expected[ch], 1e-9 * expected[ch]) << x << " " << y << " " << z;
                ++checked;
            }
    EXPECT_GT(checked, 0);
}

}  // namespace

TEST(ZonalGrids, FineLatticeSharesTheMediumsCorner) {
    const Medium m = medium_with_holes({});
    const MediumGrids g = medium_grids(m, linear_radiance(m), 3);
    EXPECT_EQ(g.dims, (std::array<int32_t, 3>{18, 18, 21}));
    EXPECT_EQ(g.origin, m.origin);
    EXPECT_FLOAT_EQ(g.voxel_size, 0.2f / 3.0f);
    EXPECT_THROW(medium_grids(m, linear_radiance(m), 0), InputError);
    EXPECT_THROW(medium_grids(m, std::vector<Rgb>(3), 2), InputError);
}

TEST(ZonalGrids, LinearRadianceIsReproducedExactly) {
    // Holes two zones from each other and the border: the medium stays two zones thick everywhere,
    // so border extrapolation is exact too; interior cells are plain trilinear interpolation.
    const Medium m = medium_with_holes({{2, 2, 2}, {3, 3, 4}});
    for (int s : {2, 3}) {
        SCOPED_TRACE(s);
        expect_linear_reproduced(m, medium_grids(m, linear_radiance(m), s), s);
    }
}

TEST(ZonalGrids, SubdivisionOneIsTheZonesThemselves) {
    const Medium m = medium_with_holes({{0, 0, 0}});
    std::vector<Rgb> L = linear_radiance(m);
    const MediumGrids g = medium_grids(m, L, 1);
    for (std::size_t v = 0; v < m.voxel_count(); ++v) {
        EXPECT_EQ(g.density[v], m.extinction[v]);
        EXPECT_EQ(g.emission[v], v == 0 ? Rgb(0.0) : m.extinction[v] * L[v]);
    }
}

TEST(ZonalGrids, EveryZoneKeepsItsPower) {
    // Light falling off fast (exp(-6 z / m), the fog box's case) with extrapolation clamped at 0
    // near a zero-radiance zone: per zone, sum of emission * fine volume = K_t L_k V_k, so the
    // whole medium's emission seen by a purely absorbing view is the zones' to rounding (1e-12).
    const Medium m = medium_with_holes({{1, 1, 1}});
    std::vector<Rgb> L(m.voxel_count());
    for (int32_t z = 0; z < m.dims[2]; ++z)
        for (int32_t y = 0; y < m.dims[1]; ++y)
            for (int32_t x = 0; x < m.dims[0]; ++x) {
                const double fall = std::exp(-6.0 * centre(m.origin, m.voxel_size, x, y, z).z);
                L[m.index(x, y, z)] = Rgb(fall, 2.0 * fall, x == 5 && y == 5 ? 0.0 : 1.0);
            }
    const int s = 3;
    const MediumGrids g = medium_grids(m, L, s);
    const double zone_volume = std::pow(double(m.voxel_size), 3), fine_volume = zone_volume / (s * s * s);
    Rgb total_zones(0.0), total_fine(0.0);
    bool varies = false;
    for (int32_t z = 0; z < m.dims[2]; ++z)
        for (int32_t y = 0; y < m.dims[1]; ++y)
            for (int32_t x = 0; x < m.dims[0]; ++x) {
                const std::size_t v = m.index(x, y, z);
                Rgb zone_sum(0.0);
                for (int k = 0; k < s; ++k)
                    for (int j = 0; j < s; ++j)
                        for (int i = 0; i < s; ++i) {
                            const Rgb& e =
                                g.emission[(x * s + i) + std::size_t(g.dims[0]) *
                                                             ((y * s + j) + std::size_t(g.dims[1]) * (z * s + k))];
                            zone_sum += e * fine_volume;
                            varies |= e.r != g.emission[(x * s) + std::size_t(g.dims[0]) *
                                                                      ((y * s) + std::size_t(g.dims[1]) * (z * s))]
                                                 .r;
                            for (int ch = 0; ch < 3; ++ch) ASSERT_GE(e[ch], 0.0);
                        }
                const Rgb expected = m.extinction[v] * (zone(m, x, y, z) ? L[v] : Rgb(0.0)) * zone_volume;
                for (int ch = 0; ch < 3; ++ch) ASSERT_NEAR(zone_sum[ch], expected[ch], 1e-12 + 1e-12 * expected[ch]);
                total_zones += expected;
                total_fine += zone_sum;
            }
    EXPECT_TRUE(varies);  // not piecewise constant
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(total_fine[ch] / total_zones[ch], 1.0, 1e-12);
}
