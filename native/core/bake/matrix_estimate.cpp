/// @file matrix_estimate.cpp
/// @brief Sampled rows' nonzeros: mean, standard error, and the total they estimate.
#include "bake/matrix_estimate.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace radiosity {

namespace {

/// The nonzeros of the sampled rows, the middle row of each stratum.
std::vector<double> sampled_fill(const Elements& elements, const RowSettings& settings, std::size_t count) {
    const std::size_t n = elements.size();
    const auto weights = CubeWeights::make(settings.resolution);
    tbb::enumerable_thread_specific<RowRenderer> renderers([&] { return RowRenderer(weights, settings); });
    tbb::enumerable_thread_specific<SparseRow> scratch;
    std::vector<double> fill(count);
    tbb::parallel_for(std::size_t(0), count, [&](std::size_t k) {
        const auto row = static_cast<int32_t>(std::min(n - 1, (2 * k + 1) * n / (2 * count)));
        SparseRow& out = scratch.local();
        renderers.local().row(elements, row, out);
        fill[k] = double(out.col.size());
    });
    return fill;
}

}  // namespace

MatrixEstimate estimate_matrix(const Elements& elements, const RowSettings& rows, const MatrixSampling& sampling) {
    MatrixEstimate estimate;
    const std::size_t n = elements.size();
    if (n == 0 || sampling.rows <= 0) return estimate;
    const std::vector<double> fill = sampled_fill(elements, rows, std::min<std::size_t>(n, sampling.rows));
    const double m = double(fill.size());
    double sum = 0.0, squares = 0.0;
    for (const double f : fill) sum += f, squares += f * f;
    estimate.rows_sampled = fill.size();
    estimate.mean_fill = sum / m;
    const double variance = fill.size() > 1 ? std::max(0.0, (squares - sum * sum / m) / (m - 1.0)) : 0.0;
    // Every row sampled: the count is exact.
    estimate.standard_error = fill.size() == n ? 0.0 : std::sqrt(variance / m);
    const auto N = static_cast<double>(std::max(rows.resolution, 0));
    const double per_row =
        std::min({estimate.mean_fill + sampling.standard_errors * estimate.standard_error, double(n), 3.0 * N * N});
    estimate.nonzeros = static_cast<std::size_t>(std::ceil(per_row * double(n)));
    estimate.bytes = (n + 1) * sizeof(int64_t) + estimate.nonzeros * (sizeof(int32_t) + sizeof(float));
    return estimate;
}

}  // namespace radiosity
