/// @file solve.h
/// @brief Solves the linked system of hierarchical radiosity (internal): Jacobi sweeps of
/// gather (every node sums its links) and push-pull (gathered light pushed down to the leaves,
/// L = E + rho G there, radiance pulled up as area means and emitters as sums).
#pragma once

#include "hierarchy/tree.h"

namespace radiosity::hr {

struct SweepResult {
    int sweeps = 0;
    double residual = 0.0;  ///< sum A |L_new - L_old| / sum A |L_new| (leaves, all channels)
    bool converged = false;
    /// False when a sweep's light was not finite (the sweeps stop there; `bad_node` is a leaf whose
    /// radiance is not, or -1): never "converged" on a residual of NaN.
    bool finite = true;
    int32_t bad_node = -1;
};

/// Pull only: leaves keep their radiance, parents and emitters follow (before the first links).
void pull(Tree& tree);

/// Sweeps until the residual falls below `tolerance` or `max_sweeps`; appends each residual to
/// `history`. Progress phase "solve"; throws Cancelled.
SweepResult solve_links(Tree& tree, double tolerance, int max_sweeps, std::vector<double>& history,
                        const ProgressFn& progress);

/// What every element gathers from the lamps alone (the solve folds it into G): per node id,
/// for the energy account (a lamp's first reflection counts as emitted, as in bake()).
std::vector<Rgb> lamp_light(Tree& tree);

/// The refinement's scale: the area-weighted mean reflected radiance L - E of the scene, largest
/// channel (what the bake shows; emitters would swamp it, a bright small lamp most of all), but
/// at least a thousandth of the brightest leaf's: a small lamp over a vast plane would otherwise
/// make the mean so small that the whole plane refines to the cap.
double reference_radiance(const Tree& tree);
constexpr double kBrightestShare = 1e-3;

}  // namespace radiosity::hr
