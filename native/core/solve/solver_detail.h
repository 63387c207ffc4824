/// @file solver_detail.h
/// @brief Pieces the solvers share: the residual norm, progress reports, the divergence guard.
#pragma once

#include "solve/shooting.h"
#include "solve/solver.h"

#include <cmath>

namespace radiosity::detail {

/// One element's share of the solvers' norm: A_i (|v_r| + |v_g| + |v_b|).
inline double weighted_l1(double area, const Rgb& v) { return area * (std::abs(v.r) + std::abs(v.g) + std::abs(v.b)); }

/// |E| in the solvers' norm (the emitted power, divided by pi).
double emitted_norm(const Elements& elements);

/// sum_j F_ij L_j over `row`, and F_ii (the element seeing itself, for concave elements).
struct Gathered {
    Rgb sum{0.0};
    double self = 0.0;
};
Gathered gather(const SparseRow& row, int32_t i, const std::vector<Rgb>& radiance);

/// Calls `progress` (when set) for phase "solve"; throws Cancelled when it returns false.
/// `radiance` holds the first `element_count` unknowns' elements (zones, if any, follow them).
void report(const ProgressFn& progress, std::size_t done, std::size_t total, double residual,
            const std::vector<Rgb>& radiance, std::size_t element_count);

/// Stops a run whose residual is not finite, or has grown for several sweeps in a row beyond the
/// first value measured (rows summing above 1 with reflectance near 1 diverge geometrically).
/// Round-off wobbles near convergence never exceed the first value, so they do not trigger it.
class DivergenceGuard {
public:
    explicit DivergenceGuard(const char* method) : method_(method) {}
    void check(double residual);

private:
    static constexpr int growth_limit = 5;
    const char* method_;
    double first_ = -1.0;
    double previous_ = 0.0;
    int growth_ = 0;
    int sweeps_ = 0;
};

/// The sweep loop of the surface and zonal systems. `sweep(L, L_entry)` moves L^k into L_entry,
/// leaves L^{k+1} in L and returns L^k's relative residual; `residual_of(L)` is L's relative
/// residual (needed once, at the sweep cap). Stops below the tolerance or at max_iterations,
/// returning the iterate whose residual it reports.
template <typename Sweep, typename Residual>
SolveResult iterate_sweeps(std::vector<Rgb> L, const SolveSettings& settings, const char* method,
                           const ProgressFn& progress, std::size_t element_count, Sweep sweep, Residual residual_of) {
    const auto cap = static_cast<std::size_t>(std::max(settings.max_iterations, 0));
    DivergenceGuard guard(method);
    SolveResult result;
    std::vector<Rgb> L_entry(L.size());
    for (std::size_t k = 0;; ++k) {  // L holds L^k here
        if (k == cap) {
            result.residual = residual_of(L);
            guard.check(result.residual);
            if (k > 0) result.residual_history.push_back(result.residual);
            result.iterations = static_cast<int>(k);
            result.converged = result.residual <= settings.tolerance;
            break;
        }
        const double residual = sweep(L, L_entry);
        guard.check(residual);
        if (k > 0) result.residual_history.push_back(residual);
        if (residual <= settings.tolerance) {
            std::swap(L, L_entry);  // return L^k, whose residual this is
            result.residual = residual;
            result.iterations = static_cast<int>(k);
            result.converged = true;
            break;
        }
        // Reports L^{k+1} with the latest measured residual (that of L^k).
        report(progress, k + 1, cap, residual, L, element_count);
    }
    result.radiance = std::move(L);
    return result;
}

/// Gauss-Seidel (in place) or Jacobi (two buffers); `emitted` = emitted_norm(elements) > 0.
SolveResult solve_sweeps(const Elements& elements, RowSource& rows, const SolveSettings& settings,
                         const ProgressFn& progress, double emitted);

/// Progressive refinement, one column of M per shot; `emitted` = emitted_norm(elements) > 0.
SolveResult solve_progressive(const Elements& elements, ShootingSource& columns, const SolveSettings& settings,
                              const ProgressFn& progress, double emitted);

}  // namespace radiosity::detail
