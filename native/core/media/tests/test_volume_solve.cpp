/// @file test_volume_solve.cpp
/// @brief The coupled surface and zone solve against exact answers: isothermal enclosures, a purely
/// scattering medium between black emitting walls, energy balance; solvers agree; cancel; the bake.
#include "bake/media_bake.h"
#include "media/zonal_solver.h"
#include "testing/test_util.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace radiosity;

namespace {

/// A closed 1 m box, walls cut into 0.25 m elements, filled with a 4^3 grid of a heterogeneous
/// medium with RGB extinction between about 0.5 and 6 per metre (optically thick across the box).
struct FoggedBox {
    test::SceneArrays scene;
    std::vector<Medium> media;
    Elements elements;
    Zones zones;
    ZonalMatrix R;

    FoggedBox(const Rgb& rho, const Rgb& wall_emission, const Rgb& albedo, double emission_per_absorption) {
        scene = test::closed_box(Vec3(1.0f), rho, wall_emission);
        elements = build_elements(scene.input(), 0.25f).elements;
        Medium m(Vec3(0.0f), 0.25f, {4, 4, 4});
        for (std::size_t v = 0; v < m.voxel_count(); ++v) {
            m.extinction[v] = Rgb(0.5 + 0.08 * v, 2.0 + std::sin(double(v)), 6.0 - 0.07 * v);
            m.albedo[v] = albedo;
            m.emission[v] = emission_per_absorption * (1.0 - albedo) * m.extinction[v];  // K_a L0
        }
        media = {m};
        zones = build_zones(media);
        ZonalFactorSettings settings;
        settings.surface_resolution = 32;
        settings.zone_resolution = 16;
        R = compute_exchange_factors(elements, media, zones, settings);
        enforce_reciprocity(R, zonal_weights(elements, zones));  // as bake_with_media
    }
};

SolveSettings tight(Method method) {
    SolveSettings s;
    s.method = method;
    s.tolerance = 1e-7;
    return s;
}

void expect_all_equal(const std::vector<Rgb>& L, const Rgb& L0, double relative, const char* what) {
    for (std::size_t x = 0; x < L.size(); ++x)
        for (int c = 0; c < 3; ++c)
            ASSERT_NEAR(L[x][c] / L0[c], 1.0, relative) << what << " unknown " << x << " channel " << c;
}

/// The unknowns but the emitting walls' back sides (emitting polygons are two-sided; the backs face
/// out of the box and see nothing: L = E): the fronts, then the zones.
std::vector<Rgb> inside(const Elements& e, const std::vector<Rgb>& L) {
    std::vector<Rgb> out = test::fronts(e, std::vector<Rgb>(L.begin(), L.begin() + e.size()));
    out.insert(out.end(), L.begin() + e.size(), L.end());
    return out;
}

}  // namespace

/// Walls with reflectance rho emitting (1 - rho) L0, a medium with albedo Omega emitting K_a L0:
/// in equilibrium every surface and zone has radiance L0 (Kirchhoff). Not just the trivial
/// black-body case: reflection and scattering must return exactly the light that is missing.
TEST(ZonalSolve, IsothermalEnclosureEverythingAtTheCommonRadiance) {
    const Rgb L0(1.0, 2.0, 0.5), rho(0.5, 0.3, 0.7), Omega(0.3, 0.6, 0.9);
    FoggedBox box(rho, (1.0 - rho) * L0, Omega, 1.0);
    for (Medium& m : box.media)
        for (Rgb& e : m.emission) e *= L0;
    box.zones = build_zones(box.media);
    for (Method method : {Method::GaussSeidel, Method::Jacobi, Method::Progressive}) {
        const SolveResult r = solve_zonal(box.elements, box.zones, box.R, tight(method));
        ASSERT_TRUE(r.converged);
        expect_all_equal(inside(box.elements, r.radiance), L0, 5e-3, "isothermal");
        // Measured far inside the 0.5% asked: rows sum to 1, so L0 solves the system.
        expect_all_equal(inside(box.elements, r.radiance), L0, 1e-5, "isothermal");
    }
}

TEST(ZonalSolve, BlackBodyEnclosureWithAbsorbingEmittingMedium) {
    const Rgb L0(0.8);
    FoggedBox box(Rgb(0.0), L0, Rgb(0.0), L0.r);
    const SolveResult r = solve_zonal(box.elements, box.zones, box.R, tight(Method::GaussSeidel));
    expect_all_equal(r.radiance, L0, 5e-3, "black body");
}

/// Black walls emitting L0 around a purely scattering, optically thick medium: every zone
/// scatters what it receives, and in equilibrium that is L0 everywhere.
TEST(ZonalSolve, PurelyScatteringMediumTakesTheWallsRadiance) {
    const Rgb L0(1.0, 0.5, 2.0);
    FoggedBox box(Rgb(0.0), L0, Rgb(1.0), 0.0);
    for (Method method : {Method::GaussSeidel, Method::Progressive}) {
        const SolveResult r = solve_zonal(box.elements, box.zones, box.R, tight(method));
        ASSERT_TRUE(r.converged);
        const std::vector<Rgb> zones(r.radiance.begin() + box.elements.size(), r.radiance.end());
        expect_all_equal(zones, L0, 5e-3, "scattering");
    }
}

/// Power emitted (pi A_i E_i by walls, 4 pi V_k emission_k = pi w_k E_k by zones) equals power absorbed
/// ((1 - rho) pi A_i H_i by walls, (1 - Omega) pi w_k H_k by zones, H = sum_y R_xy L_y).
/// With rows summing to 1 this holds when w_x R_xy = w_y R_yx: it tests the factors' reciprocity
/// (measured without enforce_reciprocity: 0.5% to 0.7% off).
TEST(ZonalSolve, EnergyBalanceEmittedEqualsAbsorbed) {
    FoggedBox box(Rgb(0.5, 0.6, 0.4), Rgb(0.0), Rgb(0.5, 0.8, 0.2), 0.0);
    // Light: one wall element glows, and a corner of the medium emits.
    box.elements.emission[5] = Rgb(10.0);
    for (std::size_t k = 0; k < 8; ++k) box.zones.emitted[k] = Rgb(3.0, 1.0, 2.0);
    const SolveResult r = solve_zonal(box.elements, box.zones, box.R, tight(Method::GaussSeidel));
    ASSERT_TRUE(r.converged);
    const std::size_t n = box.elements.size();
    Rgb emitted(0.0), absorbed(0.0);
    for (std::size_t x = 0; x < box.R.rows(); ++x) {
        Rgb H(0.0);
        for (int64_t k = box.R.row_start[x]; k < box.R.row_start[x + 1]; ++k)
            H += box.R.value(k) * r.radiance[box.R.col[k]];
        if (x < n) {
            emitted += M_PI * double(box.elements.area[x]) * box.elements.emission[x];
            absorbed += M_PI * double(box.elements.area[x]) * (1.0 - box.elements.reflectance[x]) * H;
        } else {
            const std::size_t k = x - n;
            emitted += M_PI * box.zones.weight(k) * box.zones.emitted[k];  // 4 pi V emission
            absorbed += M_PI * box.zones.weight(k) * (1.0 - box.zones.albedo[k]) * H;
        }
    }
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(absorbed[c] / emitted[c], 1.0, 1e-3) << "channel " << c;
}

TEST(ZonalSolve, MethodsAgreeAndResidualIsHonest) {
    FoggedBox box(Rgb(0.6), Rgb(0.0), Rgb(0.7), 0.0);
    box.elements.emission[3] = Rgb(5.0, 2.0, 1.0);
    const SolveResult gs = solve_zonal(box.elements, box.zones, box.R, tight(Method::GaussSeidel));
    const SolveResult pr = solve_zonal(box.elements, box.zones, box.R, tight(Method::Progressive));
    ASSERT_TRUE(gs.converged && pr.converged);
    EXPECT_LE(zonal_residual(box.elements, box.zones, box.R, gs.radiance), 1e-7 * 1.0001);
    EXPECT_LE(zonal_residual(box.elements, box.zones, box.R, pr.radiance), 1e-7 * 1.0001);
    EXPECT_NEAR(zonal_residual(box.elements, box.zones, box.R, pr.radiance), pr.residual, 1e-9);
    for (std::size_t x = 0; x < gs.radiance.size(); ++x)
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(pr.radiance[x][c], gs.radiance[x][c], 1e-5 * (1.0 + gs.radiance[x][c]));
}

/// Walls of reflectance 0.95 around a medium of albedo 0.99: plain Gauss-Seidel crawls; the
/// surface solver's over-relaxation (omega 0 = automatic: 1.75 for the albedo 0.99) reaches the same answer in
/// far fewer sweeps; omega outside (0, 2) is refused.
TEST(ZonalSolve, OverRelaxationConvergesToTheSameAnswerInFewerSweeps) {
    FoggedBox box(Rgb(0.95), Rgb(0.0), Rgb(0.99), 0.0);
    box.elements.emission[3] = Rgb(5.0, 2.0, 1.0);
    SolveSettings plain = tight(Method::GaussSeidel), over = plain;
    over.over_relaxation = 0.0;
    const SolveResult a = solve_zonal(box.elements, box.zones, box.R, plain);
    const SolveResult b = solve_zonal(box.elements, box.zones, box.R, over);
    ASSERT_TRUE(a.converged && b.converged);
    EXPECT_LT(b.iterations, a.iterations / 4);  // measured: 272 sweeps plain, 60 over-relaxed
    for (std::size_t x = 0; x < a.radiance.size(); ++x)
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(b.radiance[x][c] / a.radiance[x][c], 1.0, 1e-5) << "unknown " << x;
    over.over_relaxation = 2.0;
    EXPECT_THROW(solve_zonal(box.elements, box.zones, box.R, over), InputError);
}

TEST(ZonalSolve, CancelStopsBothMethods) {
    FoggedBox box(Rgb(0.6), Rgb(0.0), Rgb(0.7), 0.0);
    box.elements.emission[3] = Rgb(5.0);
    for (Method method : {Method::GaussSeidel, Method::Progressive}) {
        std::size_t calls = 0;
        const ProgressFn stop = [&](const Progress& p) {
            EXPECT_STREQ(p.phase, "solve");
            EXPECT_EQ(p.element_count, box.elements.size());
            return ++calls < 2;
        };
        EXPECT_THROW(solve_zonal(box.elements, box.zones, box.R, tight(method), stop), Cancelled);
    }
}

/// The whole bake: an emitting ceiling lights a fog; the grids hold K_t and K_t L.
TEST(ZonalBake, FogLitByTheCeilingGivesGridsAndColours) {
    test::SceneArrays scene = test::closed_box(Vec3(1.0f), Rgb(0.5), Rgb(0.0));
    scene.emission[3] = scene.emission[4] = scene.emission[5] = 4.0f;  // polygon 1: the ceiling
    Medium fog(Vec3(0.0f), 0.25f, {4, 4, 4});
    for (std::size_t v = 0; v < fog.voxel_count(); ++v)
        if (v % 3 != 0) fog.set(v, principled_volume(Rgb(0.8), 1.5, Rgb(0.0), 0.0, Rgb(0.0)));
    BakeSettings settings;
    settings.element_size = 0.25f;
    settings.resolution = 32;
    const ZonalBakeResult r = bake_with_media(scene.input(), {fog}, settings, 16);
    ASSERT_TRUE(r.surfaces.solve.converged);
    EXPECT_EQ(r.zones.size(), 42u);
    EXPECT_EQ(r.surfaces.solve.radiance.size(), r.surfaces.build.elements.size());
    ASSERT_EQ(r.grids.size(), 1u);
    for (std::size_t k = 0; k < r.zones.size(); ++k) {
        const std::size_t v = r.zones.voxel[k];
        EXPECT_EQ(r.grids[0].density[v], fog.extinction[v]);
        EXPECT_EQ(r.grids[0].emission[v], fog.extinction[v] * r.zone_radiance[k]);
        EXPECT_GT(r.zone_radiance[k].r, 0.0);
    }
    EXPECT_EQ(r.grids[0].emission[0], Rgb(0.0));  // voxel 0 is empty
    EXPECT_EQ(r.surfaces.colors.input_corner.size(), scene.corner_vertices.size());
}
