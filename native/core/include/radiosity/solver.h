/// @file solver.h
/// @brief Solvers of L = E + rho * F L (radiance units, RGB): Gauss-Seidel, Jacobi, progressive refinement.
///
/// One stopping rule for all: the relative residual |E - (I - rho F) L| / |E| falls below
/// `tolerance`, or `max_iterations` is reached. The norm is the area-weighted L1 norm summed over
/// RGB (emitted power), so that progressive refinement can evaluate it from its unshot power.
#pragma once

#include "radiosity/form_factors.h"

#include <vector>

namespace radiosity {

enum class Method { GaussSeidel, Jacobi, Progressive };

struct SolveSettings {
    Method method = Method::GaussSeidel;
    double tolerance = 1e-4;     ///< relative residual to stop at
    int max_iterations = 1000;   ///< sweeps; for progressive refinement one sweep = n shots
    bool ambient = false;        ///< progressive: add the seed's ambient term to the reported preview
};

struct SolveResult {
    std::vector<Rgb> radiance;          ///< per element
    int iterations = 0;                 ///< sweeps (progressive: shots / n, rounded up)
    std::size_t shots = 0;              ///< progressive refinement only
    double residual = 0.0;              ///< final relative residual
    std::vector<double> residual_history;  ///< one entry per sweep (per n shots for progressive)
    bool converged = false;
    double seconds = 0.0;
};

/// Solves with the rows of `rows`. Progress phase "solve"; throws Cancelled.
SolveResult solve(const Elements& elements, RowSource& rows, const SolveSettings& settings,
                  const ProgressFn& progress = {});

/// Relative residual |E - (I - rho F) L| / |E| of `radiance`, as the solvers measure it.
double relative_residual(const Elements& elements, RowSource& rows, const std::vector<Rgb>& radiance);

}  // namespace radiosity
