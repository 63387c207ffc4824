/// @file zonal_solver.cpp
/// @brief solve_zonal() dispatch, the residual, and the pieces the zonal solvers share.
#include "media/zonal_solver_detail.h"

#include <chrono>
#include <limits>

namespace radiosity {
namespace zonal_detail {

Terms::Terms(const Elements& elements, const Zones& zones) {
    const std::size_t n = elements.size(), z = zones.size();
    E.reserve(n + z);
    a.reserve(n + z);
    w.reserve(n + z);
    for (std::size_t i = 0; i < n; ++i) {
        E.push_back(elements.emission[i]);
        a.push_back(elements.reflectance[i]);
        w.push_back(Rgb(elements.area[i]));
    }
    for (std::size_t k = 0; k < z; ++k) {
        E.push_back(zones.emitted[k]);
        a.push_back(zones.albedo[k]);
        w.push_back(zones.weight(k));
    }
}

double Terms::emitted_norm() const {
    double sum = 0.0;
    for (std::size_t x = 0; x < size(); ++x) sum += norm(x, E[x]);
    return sum;
}

Gathered gather(const ZonalMatrix& R, std::size_t x, const std::vector<Rgb>& L) {
    Gathered g;
    for (int64_t k = R.row_start[x]; k < R.row_start[x + 1]; ++k) {
        const std::size_t y = R.col[k];
        const Rgb f = R.value(k);
        g.sum += f * L[y];
        if (y == x) g.self = f;
    }
    return g;
}

}  // namespace zonal_detail

namespace {

void check_shape(const Elements& elements, const Zones& zones, const ZonalMatrix& R) {
    if (R.rows() != elements.size() + zones.size())
        throw InputError("exchange factors have " + std::to_string(R.rows()) + " rows for " +
                         std::to_string(elements.size()) + " elements and " + std::to_string(zones.size()) + " zones");
}

}  // namespace

SolveResult solve_zonal(const Elements& elements, const Zones& zones, const ZonalMatrix& R,
                        const SolveSettings& settings, const ProgressFn& progress) {
    check_shape(elements, zones, R);
    const auto start = std::chrono::steady_clock::now();
    const zonal_detail::Terms terms(elements, zones);
    SolveResult result;
    if (terms.emitted_norm() == 0.0) {  // L = 0 solves it exactly
        result.radiance.assign(terms.size(), Rgb(0.0));
        result.converged = true;
    } else if (settings.method == Method::Progressive) {
        result = zonal_detail::solve_progressive(terms, R, settings, progress, elements.size());
    } else {
        result = zonal_detail::solve_sweeps(terms, R, settings, progress, elements.size());
    }
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

std::vector<Rgb> zonal_weights(const Elements& elements, const Zones& zones) {
    return zonal_detail::Terms(elements, zones).w;
}

double zonal_residual(const Elements& elements, const Zones& zones, const ZonalMatrix& R,
                      const std::vector<Rgb>& radiance) {
    check_shape(elements, zones, R);
    const zonal_detail::Terms t(elements, zones);
    double residual = 0.0;
    for (std::size_t x = 0; x < t.size(); ++x)
        residual += t.norm(x, t.E[x] + t.a[x] * zonal_detail::gather(R, x, radiance).sum - radiance[x]);
    const double emitted = t.emitted_norm();
    if (emitted == 0.0) return residual == 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
    return residual / emitted;
}

}  // namespace radiosity
