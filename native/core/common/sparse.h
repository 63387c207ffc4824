/// @file sparse.h
/// @brief Compressed sparse rows (CSR) of form factors, float32 values.
#pragma once

#include <cstdint>
#include <vector>

namespace radiosity {

/// One row of form factors: F_ij for the j that i sees, columns ascending.
struct SparseRow {
    std::vector<int32_t> col;
    std::vector<float> val;
    void clear() {
        col.clear();
        val.clear();
    }
};

/// Rows [row_start[i], row_start[i+1]) of col/val hold row i.
struct SparseMatrix {
    std::vector<int64_t> row_start{0};
    std::vector<int32_t> col;
    std::vector<float> val;

    std::size_t rows() const { return row_start.size() - 1; }
    std::size_t nonzeros() const { return col.size(); }
    std::size_t bytes() const {
        return row_start.size() * sizeof(int64_t) + col.size() * sizeof(int32_t) + val.size() * sizeof(float);
    }
};

}  // namespace radiosity
