/// @file solver_progressive.cpp
/// @brief Progressive refinement (seed 23.6): shoot the unshot radiance U_i of the element with the
/// largest power A_i (U_r + U_g + U_b), one column of M at a time (see shooting.h).
///
/// Shooting u from i adds dL_j = rho_j M_ji u to every L_j, so the system solved is
/// L = E + rho M L: M = F with StoredColumns, M = G (G_ji = F_ij A_i / A_j) with ReciprocalColumns.
///
/// Residual, exactly: with L = U = E at the start, every shot keeps r = E - (I - rho M) L = rho M U
/// (shooting u from i adds rho M e_i u to L and moves u from U_i to rho M e_i u). U >= 0, so
///   |r| = sum_j A_j sum_i rho_j M_ji U_i = sum_i A_i U_i . s_i,   s_i = sum_j rho_j A_j M_ji / A_i,
/// a sum over column i alone. Stored columns are all read up front, so s_i and the residual are
/// exact from the first shot. Otherwise s_i is exact once column i has been read; before that we
/// use the bound s_i <= max_j rho_j (per channel), valid when sum_j A_j M_ji / A_i <= 1 (for
/// reciprocity columns that is the row sum of F, at most 1 for hemi-cube rows). The reported
/// residual is then an upper bound until every element holding unshot radiance has shot once, and
/// exact afterwards.
#include "solve/max_tree.h"
#include "solve/solver_detail.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>

namespace radiosity::detail {
namespace {

double channel_sum(const Rgb& v) { return v.r + v.g + v.b; }

/// Unshot power sum_i A_i U_i . s_i (unnormalised residual).
double unshot_residual(const Elements& elements, const std::vector<Rgb>& U, const std::vector<Rgb>& s) {
    double r = 0.0;
    for (std::size_t i = 0; i < U.size(); ++i) r += elements.area[i] * glm::dot(U[i], s[i]);
    return r;
}

/// L plus the ambient term of Cohen et al. 1988: rho_i (1 / (1 - rho_avg)) (sum A U / sum A).
void ambient_preview(const Elements& elements, const std::vector<Rgb>& L, const std::vector<Rgb>& U,
                     std::vector<Rgb>& preview) {
    double area = 0.0;
    Rgb rho_area(0.0), unshot_area(0.0);
    for (std::size_t i = 0; i < L.size(); ++i) {
        const double A_i = elements.area[i];
        area += A_i;
        rho_area += A_i * elements.reflectance[i];
        unshot_area += A_i * U[i];
    }
    const Rgb ambient = (unshot_area / area) / (1.0 - rho_area / area);
    preview.resize(L.size());
    for (std::size_t i = 0; i < L.size(); ++i) preview[i] = L[i] + elements.reflectance[i] * ambient;
}

/// s_i = sum_j rho_j A_j M_ji / A_i from column i of M.
Rgb residual_weight(const Elements& elements, int32_t i, const SparseColumn& column) {
    Rgb s(0.0);
    for (std::size_t k = 0; k < column.row.size(); ++k) {
        const int32_t j = column.row[k];
        s += elements.reflectance[j] * (double(elements.area[j]) * column.val[k]);
    }
    return s / double(elements.area[i]);
}

}  // namespace

SolveResult solve_progressive(const Elements& elements, ShootingSource& columns, const SolveSettings& settings,
                              const ProgressFn& progress, double emitted) {
    const std::size_t n = elements.size();
    const std::size_t cap = static_cast<std::size_t>(std::max(settings.max_iterations, 0)) * n;
    const std::size_t report_every = std::max<std::size_t>(1, n / 100);
    const double tolerance = settings.tolerance * emitted;
    DivergenceGuard guard("progressive refinement");

    Rgb rho_max(0.0);
    for (const Rgb& rho : elements.reflectance) rho_max = glm::max(rho_max, rho);

    SolveResult result;
    std::vector<Rgb> L = elements.emission;
    std::vector<Rgb> U = elements.emission;
    std::vector<Rgb> s(n, rho_max);  // bound until the element's column is known
    SparseColumn column;
    if (columns.stored())
        for (std::size_t i = 0; i < n; ++i) {
            columns.column(static_cast<int32_t>(i), column);
            s[i] = residual_weight(elements, static_cast<int32_t>(i), column);
        }
    std::vector<double> power(n);
    for (std::size_t i = 0; i < n; ++i) power[i] = elements.area[i] * channel_sum(U[i]);
    MaxTree shooter(power);
    double residual = unshot_residual(elements, U, s);  // kept up to date shot by shot
    std::vector<Rgb> preview;

    auto record = [&] {  // resynchronise the running sum (no drift) and log the sweep
        residual = unshot_residual(elements, U, s);
        result.residual_history.push_back(residual / emitted);
        guard.check(residual / emitted);
    };
    std::size_t shots = 0;
    while (true) {
        if (residual <= tolerance) {
            residual = unshot_residual(elements, U, s);
            if (residual <= tolerance) {
                result.converged = true;
                break;
            }
        }
        if (shots == cap) break;
        const int32_t i = shooter.top();
        if (shooter.key(i) <= 0.0) {  // nothing left to shoot: r = rho G U = 0
            residual = 0.0;
            result.converged = true;
            break;
        }
        const Rgb u = U[i];
        residual -= elements.area[i] * glm::dot(u, s[i]);
        U[i] = Rgb(0.0);
        shooter.set(i, 0.0);

        columns.column(i, column);
        s[i] = residual_weight(elements, i, column);
        for (std::size_t k = 0; k < column.row.size(); ++k) {
            const int32_t j = column.row[k];
            const Rgb dL = elements.reflectance[j] * column.val[k] * u;
            L[j] += dL;
            U[j] += dL;
            residual += elements.area[j] * glm::dot(dL, s[j]);
            shooter.set(j, elements.area[j] * channel_sum(U[j]));
        }
        ++shots;
        if (!std::isfinite(residual)) guard.check(residual);
        if (shots % n == 0) record();
        if (shots % report_every == 0 && progress) {
            if (settings.ambient) ambient_preview(elements, L, U, preview);
            report(progress, shots, cap, residual / emitted, settings.ambient ? preview : L, n);
        }
    }
    if (shots % n != 0) record();  // the history ends with the returned residual
    result.residual = residual / emitted;
    result.shots = shots;
    result.iterations = static_cast<int>((shots + n - 1) / n);
    result.radiance = std::move(L);
    return result;
}

}  // namespace radiosity::detail
