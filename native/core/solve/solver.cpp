/// @file solver.cpp
/// @brief solve() dispatch, the relative residual, and the helpers all solvers share.
#include "solve/solver_detail.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <string>

namespace radiosity {
namespace detail {

double emitted_norm(const Elements& elements) {
    double norm = 0.0;
    for (std::size_t i = 0; i < elements.size(); ++i) norm += weighted_l1(elements.area[i], elements.emission[i]);
    return norm;
}

Gathered gather(const SparseRow& row, int32_t i, const std::vector<Rgb>& radiance) {
    Gathered g;
    for (std::size_t k = 0; k < row.col.size(); ++k) {
        const int32_t j = row.col[k];
        const double f = row.val[k];
        g.sum += f * radiance[j];
        if (j == i) g.self = f;
    }
    return g;
}

void report(const ProgressFn& progress, std::size_t done, std::size_t total, double residual,
            const std::vector<Rgb>& radiance, std::size_t element_count) {
    if (!progress) return;
    Progress p;
    p.phase = "solve";
    p.done = done;
    p.total = total;
    p.residual = residual;
    p.radiance = radiance.data();
    p.element_count = element_count;
    if (!progress(p)) throw Cancelled();
}

void DivergenceGuard::check(double residual) {
    ++sweeps_;
    if (!std::isfinite(residual))
        throw NotConverged(std::string(method_) + " diverged: the residual is not finite after sweep " +
                           std::to_string(sweeps_) + " (form-factor rows summing above 1 with reflectance near 1?)");
    if (first_ < 0.0) first_ = residual;
    growth_ = residual > previous_ && sweeps_ > 1 ? growth_ + 1 : 0;
    previous_ = residual;
    if (growth_ >= growth_limit && residual > first_)
        throw NotConverged(std::string(method_) + " diverged: the relative residual grew for " +
                           std::to_string(growth_) + " sweeps in a row to " + std::to_string(residual) + " (first " +
                           std::to_string(first_) + "); form-factor rows summing above 1 with reflectance near 1?");
}

}  // namespace detail

namespace {

/// Times the run and answers zero emission (L = 0 solves any system exactly) before dispatching.
template <class Dispatch>
SolveResult timed_solve(const Elements& elements, Dispatch&& dispatch) {
    const auto start = std::chrono::steady_clock::now();
    const double emitted = detail::emitted_norm(elements);
    SolveResult result;
    if (emitted == 0.0) {
        result.radiance.assign(elements.size(), Rgb(0.0));
        result.converged = true;
    } else {
        result = dispatch(emitted);
    }
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace

SolveResult solve(const Elements& elements, const SparseMatrix& F, const SolveSettings& settings,
                  const ProgressFn& progress) {
    return timed_solve(elements, [&](double emitted) {
        if (settings.method == Method::Progressive) {
            StoredColumns columns(F);
            return detail::solve_progressive(elements, columns, settings, progress, emitted);
        }
        StoredRows rows(F);
        return detail::solve_sweeps(elements, rows, settings, progress, emitted);
    });
}

SolveResult solve(const Elements& elements, RowSource& rows, const SolveSettings& settings,
                  const ProgressFn& progress) {
    return timed_solve(elements, [&](double emitted) {
        if (settings.method == Method::Progressive) {
            ReciprocalColumns columns(elements, rows);
            return detail::solve_progressive(elements, columns, settings, progress, emitted);
        }
        return detail::solve_sweeps(elements, rows, settings, progress, emitted);
    });
}

double recommended_over_relaxation(const Elements& elements) {
    double rho_max = 0.0;
    for (const Rgb& rho : elements.reflectance) rho_max = std::max({rho_max, rho.r, rho.g, rho.b});
    return recommended_over_relaxation(rho_max);
}

double recommended_over_relaxation(double rho_max) {
    return std::min(1.9, 2.0 / (1.0 + std::sqrt(1.0 - rho_max * rho_max)));
}

double relative_residual(const Elements& elements, RowSource& rows, const std::vector<Rgb>& radiance) {
    SparseRow row;
    double residual = 0.0;
    for (std::size_t i = 0; i < elements.size(); ++i) {
        rows.row(static_cast<int32_t>(i), row);
        const detail::Gathered g = detail::gather(row, static_cast<int32_t>(i), radiance);
        residual +=
            detail::weighted_l1(elements.area[i], elements.emission[i] + elements.reflectance[i] * g.sum - radiance[i]);
    }
    const double emitted = detail::emitted_norm(elements);
    if (emitted == 0.0) return residual == 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
    return residual / emitted;
}

}  // namespace radiosity
