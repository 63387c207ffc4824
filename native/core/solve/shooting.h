/// @file shooting.h
/// @brief What progressive refinement shoots: columns of the matrix M of the system L = E + rho M L.
///
/// Shooting the unshot radiance u of element i adds rho_j M_ji u to every L_j, so a shooter that
/// reads column i of M solves L = E + rho M L. Gathering reads rows of F; shooting needs columns.
///  - StoredColumns: the columns of a stored F (its transpose, built once). M = F exactly: the
///    system Gauss-Seidel and Jacobi solve.
///  - ReciprocalColumns: column i derived from row i of F by reciprocity, M_ji = F_ij A_i / A_j
///    =: G_ji. Needs one row at a time (rendered on demand: memory O(n)), but G = F only where
///    A_i F_ij = A_j F_ji. Centre-point hemi-cube rows break that next to shared edges, so this
///    solves a slightly different system (a closed box furnace misses E / (1 - rho) by percents).
#pragma once

#include "transport/form_factors.h"

namespace radiosity {

/// Column i of M: M_ji for the j that gather from i, rows ascending. Double, so that deriving
/// a column (A_i / A_j) adds no float rounding.
struct SparseColumn {
    std::vector<int32_t> row;
    std::vector<double> val;
};

/// Hands out columns of M, one at a time, to a single thread.
class ShootingSource {
public:
    virtual ~ShootingSource() = default;
    virtual void column(int32_t i, SparseColumn& out) = 0;
    /// True when columns are cheap to read (held in memory): the solver then reads every column
    /// once up front, so its residual is exact from the first shot.
    virtual bool stored() const = 0;
};

/// F^T in CSR: row i of the result holds column i of F (F_ji, j ascending).
SparseMatrix transpose(const SparseMatrix& F);

/// Columns of a stored F, M = F. Holds F^T: a second copy of the matrix's size.
class StoredColumns final : public ShootingSource {
public:
    explicit StoredColumns(const SparseMatrix& F) : F_transposed_(transpose(F)) {}
    void column(int32_t i, SparseColumn& out) override;
    bool stored() const override { return true; }

private:
    SparseMatrix F_transposed_;
};

/// Columns by reciprocity from the rows of F, M_ji = F_ij A_i / A_j (= F_ji only for reciprocal rows).
class ReciprocalColumns final : public ShootingSource {
public:
    ReciprocalColumns(const Elements& elements, RowSource& rows) : elements_(elements), rows_(rows) {}
    void column(int32_t i, SparseColumn& out) override;
    bool stored() const override { return false; }

private:
    const Elements& elements_;
    RowSource& rows_;
    SparseRow row_;
};

}  // namespace radiosity
