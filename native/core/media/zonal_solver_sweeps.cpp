/// @file zonal_solver_sweeps.cpp
/// @brief Gauss-Seidel (in place) and Jacobi (two buffers) on the rows of the zonal system.
///
/// As solver_sweeps.cpp: each sweep measures the exact residual of the iterate it starts from, so
/// the residual returned belongs to the radiance returned. The diagonal R_xx (a zone's light it
/// takes up itself; large for optically thick zones) is solved for, not iterated:
/// L_x = (E_x + a_x (g_x - R_xx L_x)) / (1 - a_x R_xx).
///
/// Gauss-Seidel over-relaxes as the surface solver does, L_x += omega (L_x^GS - L_x). Sound for every
/// omega in (0, 2) once the factors are reciprocal (enforce_reciprocity, as bake_with_media does):
/// scaling row x by w_x / a_x (which changes no Gauss-Seidel iterate) makes the system matrix
/// W/a - W R symmetric, and with rows of R summing to at most 1 and a < 1 it is strictly diagonally
/// dominant, so positive definite: Ostrowski-Reich. Unknowns with a = 0 are just L_x = E_x.
#include "media/zonal_solver_detail.h"

#include <algorithm>
#include <numeric>
#include <string>
#include <utility>

namespace radiosity::zonal_detail {
namespace {

Rgb solve_row(const Terms& t, std::size_t x, const Gathered& g, const Rgb& L_x) {
    return (t.E[x] + t.a[x] * (g.sum - g.self * L_x)) / (1.0 - t.a[x] * g.self);
}

double row_residual(const Terms& t, std::size_t x, const Gathered& g, const Rgb& L_x) {
    return t.norm(x, t.E[x] + t.a[x] * g.sum - L_x);
}

/// One sweep: L becomes the next iterate, L_entry the one it started from; returns the latter's
/// (unnormalised) residual.
double sweep(const Terms& t, const ZonalMatrix& R, bool jacobi, double omega, std::vector<Rgb>& L,
             std::vector<Rgb>& L_entry) {
    if (jacobi)
        std::swap(L, L_entry);
    else
        L_entry = L;
    double residual = 0.0;
    for (std::size_t x = 0; x < t.size(); ++x) {
        const Gathered entry = gather(R, x, L_entry);
        residual += row_residual(t, x, entry, L_entry[x]);
        if (jacobi)
            L[x] = solve_row(t, x, entry, L_entry[x]);
        else
            L[x] += omega * (solve_row(t, x, gather(R, x, L), L[x]) - L[x]);
    }
    return residual;
}

}  // namespace

SolveResult solve_sweeps(const Terms& t, const ZonalMatrix& R, const SolveSettings& settings,
                         const ProgressFn& progress, std::size_t element_count) {
    const bool jacobi = settings.method == Method::Jacobi;
    const double emitted = t.emitted_norm();
    // 0 = automatic: the surface solver's omega for the largest reflectance or albedo.
    const double a_max = std::accumulate(t.a.begin(), t.a.end(), 0.0, [](double m, const Rgb& a) {
        return std::max({m, a.r, a.g, a.b});
    });
    const double omega =
        settings.over_relaxation == 0.0 ? recommended_over_relaxation(a_max) : settings.over_relaxation;
    if (!(omega > 0.0 && omega < 2.0))
        throw InputError("over_relaxation must be 0 (automatic) or in (0, 2), got " + std::to_string(omega));
    return detail::iterate_sweeps(
        t.E, settings, jacobi ? "Jacobi" : "Gauss-Seidel", progress, element_count,
        [&](std::vector<Rgb>& L, std::vector<Rgb>& L_entry) {
            return sweep(t, R, jacobi, omega, L, L_entry) / emitted;
        },
        [&](const std::vector<Rgb>& L) {
            double residual = 0.0;
            for (std::size_t x = 0; x < t.size(); ++x) residual += row_residual(t, x, gather(R, x, L), L[x]);
            return residual / emitted;
        });
}

}  // namespace radiosity::zonal_detail
