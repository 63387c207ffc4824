/// @file shooting.cpp
/// @brief Columns of F for progressive refinement: a stored transpose, or reciprocity from rows.
#include "solve/shooting.h"

#include <string>

namespace radiosity {

SparseMatrix transpose(const SparseMatrix& F) {
    const std::size_t n = F.rows();
    SparseMatrix T;
    T.row_start.assign(n + 1, 0);
    for (const int32_t j : F.col) ++T.row_start[j + 1];
    for (std::size_t j = 0; j < n; ++j) T.row_start[j + 1] += T.row_start[j];
    T.col.resize(F.nonzeros());
    T.val.resize(F.nonzeros());
    // Visiting rows i in ascending order leaves every column of T ascending.
    std::vector<int64_t> next(T.row_start.begin(), T.row_start.end() - 1);
    for (std::size_t i = 0; i < n; ++i)
        for (int64_t k = F.row_start[i]; k < F.row_start[i + 1]; ++k) {
            const int64_t slot = next[F.col[k]]++;
            T.col[slot] = static_cast<int32_t>(i);
            T.val[slot] = F.val[k];
        }
    return T;
}

void StoredColumns::column(int32_t i, SparseColumn& out) {
    if (i < 0 || static_cast<std::size_t>(i) >= F_transposed_.rows())
        throw InputError("column " + std::to_string(i) + " out of range");
    const auto begin = F_transposed_.row_start[i], end = F_transposed_.row_start[i + 1];
    out.row.assign(F_transposed_.col.begin() + begin, F_transposed_.col.begin() + end);
    out.val.assign(F_transposed_.val.begin() + begin, F_transposed_.val.begin() + end);
}

void ReciprocalColumns::column(int32_t i, SparseColumn& out) {
    rows_.row(i, row_);
    const double A_i = elements_.area[i];
    out.row = row_.col;
    out.val.resize(row_.val.size());
    for (std::size_t k = 0; k < row_.val.size(); ++k)
        out.val[k] = double(row_.val[k]) * A_i / elements_.area[row_.col[k]];
}

}  // namespace radiosity
