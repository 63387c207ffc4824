#include "testing/dense_solve.h"

#include <algorithm>
#include <cmath>

namespace radiosity::test {

DenseMatrix dense(const SparseMatrix& m) {
    DenseMatrix F(m.rows(), std::vector<double>(m.rows(), 0.0));
    for (std::size_t i = 0; i < m.rows(); ++i)
        for (int64_t k = m.row_start[i]; k < m.row_start[i + 1]; ++k) F[i][m.col[k]] = m.val[k];
    return F;
}

std::vector<Rgb> direct_solve(const Elements& e, const DenseMatrix& F) {
    const std::size_t n = e.size();
    std::vector<Rgb> L(n);
    for (int c = 0; c < 3; ++c) {
        DenseMatrix M(n, std::vector<double>(n + 1, 0.0));
        for (std::size_t i = 0; i < n; ++i) {
            for (std::size_t j = 0; j < n; ++j) M[i][j] = (i == j ? 1.0 : 0.0) - e.reflectance[i][c] * F[i][j];
            M[i][n] = e.emission[i][c];
        }
        for (std::size_t k = 0; k < n; ++k) {
            std::size_t pivot = k;
            for (std::size_t i = k + 1; i < n; ++i)
                if (std::abs(M[i][k]) > std::abs(M[pivot][k])) pivot = i;
            std::swap(M[k], M[pivot]);
            for (std::size_t i = k + 1; i < n; ++i) {
                const double m = M[i][k] / M[k][k];
                for (std::size_t j = k; j <= n; ++j) M[i][j] -= m * M[k][j];
            }
        }
        for (std::size_t i = n; i-- > 0;) {
            double x = M[i][n];
            for (std::size_t j = i + 1; j < n; ++j) x -= M[i][j] * L[j][c];
            L[i][c] = x / M[i][i];
        }
    }
    return L;
}

double max_relative_error(const std::vector<Rgb>& a, const std::vector<Rgb>& b) {
    double err = 0.0, scale = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            err = std::max(err, std::abs(a[i][c] - b[i][c]));
            scale = std::max(scale, std::abs(b[i][c]));
        }
    return err / scale;
}

}  // namespace radiosity::test
