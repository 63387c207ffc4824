/// @file form_factors.cpp
/// @brief Form-factor rows: all of them in parallel into CSR, or one at a time on demand.

#include "transport/form_factors.h"

#include "common/parallel_rows.h"

#include <tbb/enumerable_thread_specific.h>

namespace radiosity {

SparseMatrix compute_form_factors(const Elements& elements, int resolution, const ProgressFn& progress) {
    RowSettings settings;
    settings.resolution = resolution;
    return compute_form_factors(elements, settings, progress);
}

SparseMatrix compute_form_factors(const Elements& elements, const RowSettings& settings, const ProgressFn& progress) {
    const std::size_t n = elements.size();
    const auto weights = CubeWeights::make(settings.resolution);
    tbb::enumerable_thread_specific<RowRenderer> renderers([&] { return RowRenderer(weights, settings); });
    std::vector<SparseRow> rows(n);

    detail::parallel_rows("form_factors", n, 16, n, progress, [&](std::size_t i) {
        renderers.local().row(elements, static_cast<int32_t>(i), rows[i]);
        return true;
    });

    SparseMatrix matrix;
    matrix.row_start.resize(n + 1);
    matrix.row_start[0] = 0;
    for (std::size_t i = 0; i < n; ++i)
        matrix.row_start[i + 1] = matrix.row_start[i] + static_cast<int64_t>(rows[i].col.size());
    matrix.col.reserve(matrix.row_start[n]);
    matrix.val.reserve(matrix.row_start[n]);
    for (SparseRow& row : rows) {
        matrix.col.insert(matrix.col.end(), row.col.begin(), row.col.end());
        matrix.val.insert(matrix.val.end(), row.val.begin(), row.val.end());
        row = SparseRow();
    }
    return matrix;
}

void StoredRows::row(int32_t i, SparseRow& out) {
    if (i < 0 || static_cast<std::size_t>(i) >= matrix_.rows())
        throw InputError("row " + std::to_string(i) + " out of range");
    const auto begin = matrix_.row_start[i], end = matrix_.row_start[i + 1];
    out.col.assign(matrix_.col.begin() + begin, matrix_.col.begin() + end);
    out.val.assign(matrix_.val.begin() + begin, matrix_.val.begin() + end);
}

HemicubeRows::HemicubeRows(const Elements& elements, int resolution)
    : HemicubeRows(elements, [&] {
          RowSettings settings;
          settings.resolution = resolution;
          return settings;
      }()) {}

HemicubeRows::HemicubeRows(const Elements& elements, const RowSettings& settings)
    : elements_(elements), renderer_(CubeWeights::make(settings.resolution), settings) {}

void HemicubeRows::row(int32_t i, SparseRow& out) {
    if (i < 0 || static_cast<std::size_t>(i) >= elements_.size())
        throw InputError("row " + std::to_string(i) + " out of range");
    renderer_.row(elements_, i, out);
}

}  // namespace radiosity
