/// @file zonal_solver_progressive.cpp
/// @brief Progressive refinement on the zonal system: shoot the unshot radiance U_x of the unknown
/// (element or zone) with the largest power sum_c w_x,c U_x,c along column x of R.
///
/// Shooting u from x adds a_y R_yx u to L_y and U_y, so this solves the system the sweeps solve.
/// As in solver_progressive.cpp the residual is exactly sum_x w_x U_x . s_x with
/// s_x = sum_y a_y w_y R_yx / w_x (per channel), known for every x because R^T is held.
#include "media/zonal_solver_detail.h"
#include "solve/max_tree.h"

#include <algorithm>

namespace radiosity::zonal_detail {
namespace {

double power(const Terms& t, std::size_t x, const Rgb& U) { return t.norm(x, U); }

}  // namespace

SolveResult solve_progressive(const Terms& t, const ZonalMatrix& R, const SolveSettings& settings,
                              const ProgressFn& progress, std::size_t element_count) {
    const std::size_t n = t.size();
    const std::size_t cap = static_cast<std::size_t>(std::max(settings.max_iterations, 0)) * n;
    const std::size_t report_every = std::max<std::size_t>(1, n / 100);
    const double emitted = t.emitted_norm(), tolerance = settings.tolerance * emitted;
    detail::DivergenceGuard guard("progressive refinement");
    const ZonalMatrix columns = transpose(R);

    std::vector<Rgb> s(n, Rgb(0.0));
    for (std::size_t x = 0; x < n; ++x) {
        for (int64_t k = columns.row_start[x]; k < columns.row_start[x + 1]; ++k) {
            const std::size_t y = columns.col[k];
            s[x] += t.a[y] * t.w[y] * columns.value(k);
        }
        for (int ch = 0; ch < 3; ++ch) s[x][ch] = t.w[x][ch] > 0.0 ? s[x][ch] / t.w[x][ch] : 0.0;
    }
    auto unshot_residual = [&](const std::vector<Rgb>& U) {
        double r = 0.0;
        for (std::size_t x = 0; x < n; ++x) r += t.norm(x, U[x] * s[x]);
        return r;
    };

    SolveResult result;
    std::vector<Rgb> L = t.E, U = t.E;
    std::vector<double> keys(n);
    for (std::size_t x = 0; x < n; ++x) keys[x] = power(t, x, U[x]);
    detail::MaxTree shooter(keys);
    double residual = unshot_residual(U);
    auto record = [&] {  // resynchronise the running sum and log the sweep
        residual = unshot_residual(U);
        result.residual_history.push_back(residual / emitted);
        guard.check(residual / emitted);
    };
    std::size_t shots = 0;
    while (true) {
        if (residual <= tolerance) {
            residual = unshot_residual(U);
            if (residual <= tolerance) {
                result.converged = true;
                break;
            }
        }
        if (shots == cap) break;
        const int32_t x = shooter.top();
        if (shooter.key(x) <= 0.0) {
            residual = 0.0;
            result.converged = true;
            break;
        }
        const Rgb u = U[x];
        residual -= t.norm(x, u * s[x]);
        U[x] = Rgb(0.0);
        shooter.set(x, 0.0);
        for (int64_t k = columns.row_start[x]; k < columns.row_start[x + 1]; ++k) {
            const int32_t y = columns.col[k];
            const Rgb dL = t.a[y] * columns.value(k) * u;
            L[y] += dL;
            U[y] += dL;
            residual += t.norm(y, dL * s[y]);
            shooter.set(y, power(t, y, U[y]));
        }
        ++shots;
        if (!std::isfinite(residual)) guard.check(residual);
        if (shots % n == 0) record();
        if (shots % report_every == 0) detail::report(progress, shots, cap, residual / emitted, L, element_count);
    }
    if (shots % n != 0) record();
    result.residual = residual / emitted;
    result.shots = shots;
    result.iterations = static_cast<int>((shots + n - 1) / n);
    result.radiance = std::move(L);
    return result;
}

}  // namespace radiosity::zonal_detail
