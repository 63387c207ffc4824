/// @file form_factors.h
/// @brief Form-factor rows for every element: stored as a sparse matrix or computed on demand.
#pragma once

#include "transport/row_renderer.h"

namespace radiosity {

/// Gives row i of F (F_ij, j = 0..n-1). Implementations are safe to call from one thread at a time.
class RowSource {
public:
    virtual ~RowSource() = default;
    virtual void row(int32_t i, SparseRow& out) = 0;
};

/// F for all elements, one hemi-cube per element at its centre, parallel over elements (TBB).
/// Reports progress as phase "form_factors" (done = hemi-cubes finished); throws Cancelled.
SparseMatrix compute_form_factors(const Elements& elements, int resolution, const ProgressFn& progress = {});
/// As above, with rows computed as `settings` asks (orientation averaging, near-field correction).
SparseMatrix compute_form_factors(const Elements& elements, const RowSettings& settings,
                                  const ProgressFn& progress = {});

/// Rows read from a stored matrix.
class StoredRows final : public RowSource {
public:
    explicit StoredRows(const SparseMatrix& matrix) : matrix_(matrix) {}
    void row(int32_t i, SparseRow& out) override;

private:
    const SparseMatrix& matrix_;
};

/// Rows rendered on demand with one hemi-cube (memory O(n)); progressive refinement uses this.
class HemicubeRows final : public RowSource {
public:
    HemicubeRows(const Elements& elements, int resolution);
    HemicubeRows(const Elements& elements, const RowSettings& settings);
    void row(int32_t i, SparseRow& out) override;

private:
    const Elements& elements_;
    RowRenderer renderer_;
};

}  // namespace radiosity
