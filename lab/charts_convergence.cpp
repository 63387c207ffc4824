/// @file charts_convergence.cpp
/// @brief Chart 3: relative residual against sweep and time, each solver, rho 0.5 / 0.9 / 0.99.
///
/// The Cornell box's geometry (closed, ceiling light, two blocks) with one reflectance everywhere,
/// 0.1 m elements, hemi-cube resolution 64, stored matrix (computed once per rho, not timed).
/// Residuals come from the solvers' progress reports: Gauss-Seidel and Jacobi once per sweep,
/// progressive refinement every 10% of a sweep (n shots).
#include "charts.h"

#include "solve/solver.h"
#include "testing/test_util.h"

#include <cstdio>

namespace radiosity::charts {

void convergence(const std::string& csv_path) {
    FILE* out = std::fopen(csv_path.c_str(), "w");
    std::fprintf(out, "rho,method,sweep,seconds,residual\n");
    for (double rho : {0.5, 0.9, 0.99}) {
        test::SceneArrays scene = test::cornell_box();
        for (float& r : scene.reflectance) r = static_cast<float>(rho);
        const Elements e = build_elements(scene.input(), 0.1f).elements;
        const SparseMatrix F = compute_form_factors(e, 64);
        struct Run {
            const char* name;
            Method method;
            double omega;
        };
        const Run runs[] = {{"gauss_seidel", Method::GaussSeidel, 1.0},
                            {"jacobi", Method::Jacobi, 1.0},
                            {"progressive", Method::Progressive, 1.0},
                            {"sor", Method::GaussSeidel, recommended_over_relaxation(e)}};
        for (const Run& run : runs) {
            SolveSettings s;
            s.method = run.method;
            s.over_relaxation = run.omega;
            s.tolerance = 1e-6;
            s.max_iterations = 4000;
            const auto start = std::chrono::steady_clock::now();
            const double n = double(e.size());
            int reports = 0;
            auto record = [&](const Progress& p) {
                // Progressive refinement reports every 1% of a sweep: keep every 10th (CSV size).
                if (run.method == Method::Progressive && reports++ % 10 != 0) return true;
                // Sweeps report done = k + 1 with the residual of L^k; shots report done = shots.
                const double sweep = run.method == Method::Progressive ? double(p.done) / n : double(p.done - 1);
                std::fprintf(out, "%g,%s,%.4f,%.6e,%.6e\n", rho, run.name, sweep, seconds_since(start), p.residual);
                return true;
            };
            const SolveResult r = solve(e, F, s, record);
            std::printf("rho %.2f %-12s %zu elements: %d sweeps, residual %.1e, %.3f s\n", rho, run.name, e.size(),
                        r.iterations, r.residual, r.seconds);
        }
    }
    std::fclose(out);
}

}  // namespace radiosity::charts
