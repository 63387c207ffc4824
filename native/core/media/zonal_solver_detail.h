/// @file zonal_solver_detail.h
/// @brief What the zonal solvers share: per-unknown emission, albedo and norm weight; gathering a row.
#pragma once

#include "media/zonal_solver.h"
#include "solve/solver_detail.h"

#include <vector>

namespace radiosity::zonal_detail {

/// E_x, a_x and w_x of every unknown (elements, then zones).
struct Terms {
    std::vector<Rgb> E, a, w;
    Terms(const Elements& elements, const Zones& zones);
    std::size_t size() const { return E.size(); }
    /// |v| in the solvers' norm for unknown x: sum over channels of w |v|.
    double norm(std::size_t x, const Rgb& v) const {
        return w[x].r * std::abs(v.r) + w[x].g * std::abs(v.g) + w[x].b * std::abs(v.b);
    }
    double emitted_norm() const;
};

/// sum_y R_xy L_y and R_xx.
struct Gathered {
    Rgb sum{0.0}, self{0.0};
};
Gathered gather(const ZonalMatrix& R, std::size_t x, const std::vector<Rgb>& L);

SolveResult solve_sweeps(const Terms& t, const ZonalMatrix& R, const SolveSettings& settings,
                         const ProgressFn& progress, std::size_t element_count);
SolveResult solve_progressive(const Terms& t, const ZonalMatrix& R, const SolveSettings& settings,
                              const ProgressFn& progress, std::size_t element_count);

}  // namespace radiosity::zonal_detail
