/// @file solver_detail.h
/// @brief Pieces the solvers share: the residual norm, progress reports, the divergence guard.
#pragma once

#include "radiosity/shooting.h"
#include "radiosity/solver.h"

#include <cmath>

namespace radiosity::detail {

/// One element's share of the solvers' norm: A_i (|v_r| + |v_g| + |v_b|).
inline double weighted_l1(double area, const Rgb& v) {
    return area * (std::abs(v.r) + std::abs(v.g) + std::abs(v.b));
}

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

/// Gauss-Seidel (in place) or Jacobi (two buffers); `emitted` = emitted_norm(elements) > 0.
SolveResult solve_sweeps(const Elements& elements, RowSource& rows, const SolveSettings& settings,
                         const ProgressFn& progress, double emitted);

/// Progressive refinement, one column of M per shot; `emitted` = emitted_norm(elements) > 0.
SolveResult solve_progressive(const Elements& elements, ShootingSource& columns, const SolveSettings& settings,
                              const ProgressFn& progress, double emitted);

}  // namespace radiosity::detail
