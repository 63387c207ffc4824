/// @file solver_sweeps.cpp
/// @brief Gauss-Seidel (in place, as Cohen & Greenberg 1985 solve it) and Jacobi (two buffers) on the rows of F.
///
/// Each sweep reads every row once. While it computes the next iterate it also measures the exact
/// residual of the iterate it started from, so the residual we stop on and return belongs to the
/// radiance we return: when the iterate L^k entering sweep k+1 is below tolerance, sweep k+1's
/// output is dropped and L^k is returned. At the sweep cap one measuring pass gives L^cap's residual.
///
/// A sweep whose rows are rendered on demand (one hemi-cube each) takes minutes on a large scene,
/// so a sweep that runs long reports its rows too: phase "solve rows", done = rows swept.
#include "solve/solver_detail.h"

#include <algorithm>
#include <chrono>
#include <string>
#include <utility>

namespace radiosity::detail {
namespace {

/// Reports the rows of a sweep that has run for more than kInterval since its last report (also a
/// chance to cancel); quick sweeps, as on a stored matrix, never do.
class RowProgress {
public:
    RowProgress(const ProgressFn& progress, std::size_t element_count) : progress_(progress), count_(element_count) {}

    void start() { last_ = Clock::now(); }

    void row_done(std::size_t i, const std::vector<Rgb>& L) {
        if (!progress_ || (i + 1) % kRowsPerCheck != 0 || Clock::now() - last_ < kInterval) return;
        last_ = Clock::now();
        Progress p;
        p.phase = "solve rows";
        p.done = i + 1;
        p.total = count_;
        p.radiance = L.data();
        p.element_count = count_;
        if (!progress_(p)) throw Cancelled();
    }

private:
    using Clock = std::chrono::steady_clock;
    static constexpr std::size_t kRowsPerCheck = 16;
    static constexpr std::chrono::milliseconds kInterval{500};
    const ProgressFn& progress_;
    std::size_t count_;
    Clock::time_point last_;
};

/// Row i of the system solved for L_i, F_ii included: L_i = (E_i + rho_i (g_i - F_ii L_i)) / (1 - rho_i F_ii).
Rgb solve_row(const Elements& elements, std::size_t i, const Gathered& g, const Rgb& L_i) {
    const Rgb& rho = elements.reflectance[i];
    return (elements.emission[i] + rho * (g.sum - g.self * L_i)) / (1.0 - rho * g.self);
}

/// Residual r_i = E_i + rho_i sum_j F_ij L_j - L_i in the solvers' norm.
double row_residual(const Elements& elements, std::size_t i, const Gathered& g, const Rgb& L_i) {
    return weighted_l1(elements.area[i], elements.emission[i] + elements.reflectance[i] * g.sum - L_i);
}

/// Gauss-Seidel: on return L is the next iterate, L_entry the one it started from.
/// Returns the residual of L_entry (unnormalised).
double gauss_seidel_sweep(const Elements& elements, RowSource& rows, std::vector<Rgb>& L, std::vector<Rgb>& L_entry,
                          SparseRow& row, double omega, RowProgress& tell) {
    L_entry = L;
    tell.start();
    double residual = 0.0;
    for (std::size_t i = 0; i < elements.size(); ++i) {
        const auto i32 = static_cast<int32_t>(i);
        rows.row(i32, row);
        // The entry iterate's gather measures its residual; the current (partly updated) one
        // gives the Gauss-Seidel update.
        residual += row_residual(elements, i, gather(row, i32, L_entry), L_entry[i]);
        L[i] += omega * (solve_row(elements, i, gather(row, i32, L), L[i]) - L[i]);
        tell.row_done(i, L);
    }
    return residual;
}

/// Jacobi: same contract as gauss_seidel_sweep.
double jacobi_sweep(const Elements& elements, RowSource& rows, std::vector<Rgb>& L, std::vector<Rgb>& L_entry,
                    SparseRow& row, RowProgress& tell) {
    std::swap(L, L_entry);
    tell.start();
    double residual = 0.0;
    for (std::size_t i = 0; i < elements.size(); ++i) {
        const auto i32 = static_cast<int32_t>(i);
        rows.row(i32, row);
        const Gathered g = gather(row, i32, L_entry);
        residual += row_residual(elements, i, g, L_entry[i]);
        L[i] = solve_row(elements, i, g, L_entry[i]);
        tell.row_done(i, L_entry);  // L holds old values beyond row i
    }
    return residual;
}

}  // namespace

SolveResult solve_sweeps(const Elements& elements, RowSource& rows, const SolveSettings& settings,
                         const ProgressFn& progress, double emitted) {
    const bool jacobi = settings.method == Method::Jacobi;
    // 0 = automatic: the add-on asks for the core's measured omega rather than copying its formula.
    const double omega =
        settings.over_relaxation == 0.0 ? recommended_over_relaxation(elements) : settings.over_relaxation;
    if (!(omega > 0.0 && omega < 2.0))
        throw InputError("over_relaxation must be 0 (automatic) or in (0, 2), got " + std::to_string(omega));
    SparseRow row;
    RowProgress tell(progress, elements.size());
    return iterate_sweeps(
        elements.emission /* the classic start: B = E */, settings, jacobi ? "Jacobi" : "Gauss-Seidel", progress,
        elements.size(),
        [&](std::vector<Rgb>& L, std::vector<Rgb>& L_entry) {
            return (jacobi ? jacobi_sweep(elements, rows, L, L_entry, row, tell)
                           : gauss_seidel_sweep(elements, rows, L, L_entry, row, omega, tell)) /
                   emitted;
        },
        [&](const std::vector<Rgb>& L) { return relative_residual(elements, rows, L); });
}

}  // namespace radiosity::detail
