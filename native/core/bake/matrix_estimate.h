/// @file matrix_estimate.h
/// @brief The stored form-factor matrix's size from a sample of its rows.
///
/// A row holds one nonzero per element its hemi-cube sees, so the matrix holds the sum of what each
/// element sees. matrix_bytes_bound assumes each sees min(n, 3 N^2) elements; an interior's element
/// sees a few per cent of them (oa_bases3: 170 MB stored against a bound of 2.7 GB). Rendering the
/// rows of a stratified sample of the elements and counting their nonzeros estimates the sum
/// (survey sampling's estimator of a total, Cochran 1977, ch. 5: stratified by the elements' order,
/// which follows their polygons, so the strata are places in the scene).
#pragma once

#include "transport/row_renderer.h"

#include <cstddef>

namespace radiosity {

/// How many rows are sampled, and the margin the estimate keeps above the sample's mean fill.
struct MatrixSampling {
    int rows = 256;
    /// Standard errors of the sample's mean added to it. The standard error is that of a simple
    /// random sample (sd / sqrt(m)), which a stratified sample's does not exceed (Cochran 1977,
    /// 5.6), so the margin holds at least this many standard errors.
    double standard_errors = 3.0;
};

struct MatrixEstimate {
    std::size_t rows_sampled = 0;
    double mean_fill = 0.0;       ///< nonzeros per sampled row
    double standard_error = 0.0;  ///< of mean_fill, sd / sqrt(rows_sampled)
    std::size_t nonzeros = 0;     ///< n (mean_fill + margin), at most the bound's n min(n, 3 N^2)
    std::size_t bytes = 0;        ///< SparseMatrix::bytes() of a matrix of that many nonzeros
};

/// Renders the rows of `sampling.rows` elements (the middle of each of as many equal strata of the
/// elements' order; every row when there are fewer) as `rows` would, in parallel, and estimates the
/// matrix's nonzeros and bytes with the margin.
MatrixEstimate estimate_matrix(const Elements& elements, const RowSettings& rows, const MatrixSampling& sampling = {});

}  // namespace radiosity
