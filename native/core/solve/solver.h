/// @file solver.h
/// @brief Solvers of L = E + rho * F L (radiance units, RGB): Gauss-Seidel, Jacobi, progressive refinement.
///
/// Which system each entry point solves:
///  - solve(elements, F): all three methods solve L = E + rho F L with the stored F. Gauss-Seidel
///    and Jacobi gather its rows; progressive refinement shoots its columns (StoredColumns).
///  - solve(elements, rows): Gauss-Seidel and Jacobi gather rows of F, as above. Progressive
///    refinement shoots columns derived from the rows by reciprocity (ReciprocalColumns), so it
///    solves L = E + rho G L, G_ji = F_ij A_i / A_j: F only where rows are reciprocal, which
///    centre-point hemi-cube rows are not next to shared edges. This is the O(n)-memory path.
///
/// One stopping rule for all: the relative residual |E - (I - rho F) L| / |E| falls below
/// `tolerance`, or `max_iterations` is reached. The norm is the area-weighted L1 norm summed over
/// RGB (emitted power), so that progressive refinement can evaluate it from its unshot power.
#pragma once

#include "transport/form_factors.h"

#include <vector>

namespace radiosity {

enum class Method { GaussSeidel, Jacobi, Progressive };

struct SolveSettings {
    Method method = Method::GaussSeidel;
    double tolerance = 1e-4;    ///< relative residual to stop at
    int max_iterations = 1000;  ///< sweeps; for progressive refinement one sweep = n shots
    bool ambient =
        false;  ///< progressive: add the ambient term of Cohen, Chen, Wallace & Greenberg 1988 to the reported preview
    /// Gauss-Seidel only (surfaces and the zonal system): successive over-relaxation, L_i += omega (L_i^GS - L_i),
    /// omega in (0, 2). 1 = plain Gauss-Seidel; 0 = automatic, recommended_over_relaxation(elements), the measured
    /// choice. Pays off where reflectance is near 1 (docs/stability.md).
    double over_relaxation = 1.0;
};

struct SolveResult {
    std::vector<Rgb> radiance;             ///< per element
    int iterations = 0;                    ///< sweeps (progressive: shots / n, rounded up)
    std::size_t shots = 0;                 ///< progressive refinement only
    double residual = 0.0;                 ///< final relative residual
    std::vector<double> residual_history;  ///< one entry per sweep (per n shots for progressive)
    bool converged = false;
    double seconds = 0.0;
};

/// Solves L = E + rho F L with the stored F, whatever the method. Progressive refinement holds
/// F^T besides F (twice the matrix's memory). Progress phase "solve"; throws Cancelled.
SolveResult solve(const Elements& elements, const SparseMatrix& F, const SolveSettings& settings,
                  const ProgressFn& progress = {});

/// Solves with rows of F read one at a time: gathering solves with F, progressive refinement with
/// G (reciprocity, see above). Progress phase "solve"; throws Cancelled.
SolveResult solve(const Elements& elements, RowSource& rows, const SolveSettings& settings,
                  const ProgressFn& progress = {});

/// omega for Gauss-Seidel from the largest reflectance: 2 / (1 + sqrt(1 - rho_max^2)), the optimum
/// of SOR when Jacobi's spectral radius is rho_max (a closed room), capped at 1.9.
double recommended_over_relaxation(const Elements& elements);
/// The same from the largest reflectance (or a zone's albedo) rho_max in [0, 1].
double recommended_over_relaxation(double rho_max);

/// Relative residual |E - (I - rho F) L| / |E| of `radiance` with the rows of F, as the gathering
/// solvers measure it (and progressive refinement on stored columns).
double relative_residual(const Elements& elements, RowSource& rows, const std::vector<Rgb>& radiance);

}  // namespace radiosity
