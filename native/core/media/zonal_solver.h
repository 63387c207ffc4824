/// @file zonal_solver.h
/// @brief The coupled surface and zone system, the zonal method's surface and zone equations (Rushmeier & Torrance
/// 1987) in radiance units, solved by Gauss-Seidel, Jacobi or progressive refinement with the surface solvers' stopping
/// rule.
///
/// For every unknown x (elements 0 .. n-1, then zones), with R the exchange factors of zonal.h:
///   L_x = E_x + a_x sum_y R_xy L_y
///  - element i: E = emitted radiance, a = reflectance. (15) divided by pi A_i, with
///    S_jS_i = A_i R_ij and V_kS_i = A_i R_ik by the zonal method's reciprocity.
///  - zone k: E = emission_k / K_t,k (Zones::emitted), a = albedo Omega_k. (16) divided by
///    4 pi K_t,k V_k = pi w_k: 4 K_t V_k B_k = 4 K_a E_k V_k + Omega_k {sum_j B_j S_jV_k + sum_m B_m V_mV_k}
///    with B = pi L, S_jV_k = V_kS_j = w_k R_kj and V_mV_k = w_k R_km, and K_a E_k / pi = the
///    emission coefficient (radiance per metre), so K_a E_k / (pi K_t) = emission_k / K_t,k.
///    L_k is the zone's radiance J_k = B_k / pi of the zonal method.
/// Stopping rule (solver.h): relative residual |E - (I - a R) L| / |E| in the L1 norm weighted per
/// channel by w_x = A_i for elements and 4 K_t,k V_k for zones (outgoing power over pi, per unit radiance).
#pragma once

#include "media/zonal.h"
#include "solve/solver.h"

namespace radiosity {

/// Solves the coupled system; SolveResult::radiance holds elements, then zones. Method::Progressive
/// holds R^T besides R. Progress phase "solve": Progress::radiance points at all unknowns,
/// Progress::element_count counts the elements (zones follow them). Throws Cancelled.
SolveResult solve_zonal(const Elements& elements, const Zones& zones, const ZonalMatrix& R,
                        const SolveSettings& settings, const ProgressFn& progress = {});

/// w_x per unknown: element area, zone 4 K_t V per channel (the norm's weights; enforce_reciprocity's).
std::vector<Rgb> zonal_weights(const Elements& elements, const Zones& zones);

/// Relative residual |E - (I - a R) L| / |E| of `radiance` (elements, then zones).
double zonal_residual(const Elements& elements, const Zones& zones, const ZonalMatrix& R,
                      const std::vector<Rgb>& radiance);

}  // namespace radiosity
