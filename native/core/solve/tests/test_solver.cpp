/// @file test_solver.cpp
/// @brief Solvers against a dense direct solve and the furnace, on synthetic reciprocal matrices
/// (and on real hemi-cube rows in test_bake.cpp): residuals, cancel, divergence, zero emission.
#include "solve/shooting.h"
#include "solve/solver.h"

#include "testing/dense_solve.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace radiosity {
namespace {

using test::max_relative_error;

/// Rows of a matrix held as one SparseRow per element (the test's own StoredRows).
class MatrixRows final : public RowSource {
public:
    explicit MatrixRows(std::vector<SparseRow> rows) : rows_(std::move(rows)) {}
    void row(int32_t i, SparseRow& out) override {
        out = rows_[i];
        ++calls;
    }
    double at(int32_t i, int32_t j) const {
        const SparseRow& r = rows_[i];
        for (std::size_t k = 0; k < r.col.size(); ++k)
            if (r.col[k] == j) return r.val[k];
        return 0.0;
    }
    std::size_t calls = 0;

private:
    std::vector<SparseRow> rows_;
};

struct System {
    Elements elements;
    std::vector<SparseRow> rows;
};

/// A random sparse enclosure with exact reciprocity: symmetric weights W_ij = A_i F_ij, areas
/// A_i = sum_j W_ij / s_i, so row i of F sums to s_i drawn from [row_sum_lo, row_sum_hi].
/// `self` gives some elements a diagonal F_ii (concave elements see themselves).
System random_enclosure(int n, double row_sum_lo, double row_sum_hi, bool self, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<std::vector<double>> W(n, std::vector<double>(n, 0.0));
    for (int i = 0; i < n; ++i) {
        if (self && unit(rng) < 0.3) W[i][i] = 0.3 * unit(rng);
        for (int j = i + 1; j < n; ++j)
            if (unit(rng) < 0.5) W[i][j] = W[j][i] = 0.1 + unit(rng);
        W[i][(i + 1) % n] = W[(i + 1) % n][i] = 0.5;  // connected
    }
    System s;
    Elements& e = s.elements;
    s.rows.resize(n);
    for (int i = 0; i < n; ++i) {
        double w = 0.0;
        for (int j = 0; j < n; ++j) w += W[i][j];
        const double row_sum = row_sum_lo + (row_sum_hi - row_sum_lo) * unit(rng);
        const double area = w / row_sum;
        for (int j = 0; j < n; ++j)
            if (W[i][j] > 0.0) {
                s.rows[i].col.push_back(j);
                s.rows[i].val.push_back(static_cast<float>(W[i][j] / area));
            }
        e.centre.push_back(Vec3(0.0f));
        e.area.push_back(static_cast<float>(area));
        e.reflectance.push_back(Rgb(0.2 + 0.7 * unit(rng), 0.1 + 0.5 * unit(rng), 0.8 * unit(rng)));
        e.emission.push_back(unit(rng) < 0.2 ? Rgb(5.0 * unit(rng), 2.0 * unit(rng), 1.0) : Rgb(0.0));
    }
    e.emission[0] = Rgb(1.0, 2.0, 3.0);
    return s;
}

/// The rows as a dense matrix, for the direct solve.
test::DenseMatrix dense(const Elements& e, const MatrixRows& rows) {
    const auto n = static_cast<int32_t>(e.size());
    test::DenseMatrix F(n, std::vector<double>(n, 0.0));
    for (int32_t i = 0; i < n; ++i)
        for (int32_t j = 0; j < n; ++j) F[i][j] = rows.at(i, j);
    return F;
}

std::vector<Rgb> direct_solve(const Elements& e, const MatrixRows& rows) {
    return test::direct_solve(e, dense(e, rows));
}

bool all_finite(const std::vector<Rgb>& v) {
    for (const Rgb& x : v)
        if (!std::isfinite(x.r) || !std::isfinite(x.g) || !std::isfinite(x.b)) return false;
    return true;
}

/// The rows as a stored CSR matrix.
SparseMatrix to_matrix(const std::vector<SparseRow>& rows) {
    SparseMatrix F;
    for (const SparseRow& r : rows) {
        F.col.insert(F.col.end(), r.col.begin(), r.col.end());
        F.val.insert(F.val.end(), r.val.begin(), r.val.end());
        F.row_start.push_back(static_cast<int64_t>(F.col.size()));
    }
    return F;
}

/// Breaks reciprocity as hemi-cube rows do: every F_ij scaled by a factor in [0.8, 1.0], so
/// A_i F_ij != A_j F_ji and shooting by reciprocity would solve a different system.
void break_reciprocity(System& sys, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> factor(0.8, 1.0);
    for (SparseRow& r : sys.rows)
        for (float& v : r.val) v = static_cast<float>(v * factor(rng));
}

const Method methods[] = {Method::GaussSeidel, Method::Jacobi, Method::Progressive};

SolveSettings settings_for(Method m, double tolerance, int max_iterations = 10000) {
    SolveSettings s;
    s.method = m;
    s.tolerance = tolerance;
    s.max_iterations = max_iterations;
    return s;
}

TEST(Solver, AllMethodsMatchDenseDirectSolve) {
    const System sys = random_enclosure(60, 0.6, 0.98, true, 7);
    MatrixRows rows(sys.rows);
    const std::vector<Rgb> truth = direct_solve(sys.elements, rows);
    for (Method m : methods) {
        const SolveResult r = solve(sys.elements, rows, settings_for(m, 1e-10));
        EXPECT_TRUE(r.converged);
        EXPECT_LT(max_relative_error(r.radiance, truth), 1e-5) << "method " << int(m);
        EXPECT_TRUE(all_finite(r.radiance));
        std::printf("method %d: %d sweeps, %zu shots, residual %.3g, max rel error %.3g\n", int(m), r.iterations,
                    r.shots, r.residual, max_relative_error(r.radiance, truth));
    }
}

TEST(Solver, TransposeGivesTheColumns) {
    const System sys = random_enclosure(30, 0.6, 0.9, true, 13);
    const MatrixRows rows(sys.rows);
    const SparseMatrix T = transpose(to_matrix(sys.rows));
    ASSERT_EQ(T.rows(), 30u);
    std::size_t nonzeros = 0;
    for (const SparseRow& r : sys.rows) nonzeros += r.col.size();
    ASSERT_EQ(T.nonzeros(), nonzeros);
    for (int32_t i = 0; i < 30; ++i)
        for (int64_t k = T.row_start[i]; k < T.row_start[i + 1]; ++k) {
            if (k > T.row_start[i]) EXPECT_LT(T.col[k - 1], T.col[k]);  // ascending
            EXPECT_EQ(T.val[k], rows.at(T.col[k], i));
        }
}

TEST(Solver, StoredMatrixSolvesTheNonReciprocalSystemExactly) {
    // On a stored F every method solves L = E + rho F L, reciprocal or not: progressive refinement
    // shoots columns of F. Shooting by reciprocity from the rows solves with G instead.
    System sys = random_enclosure(60, 0.6, 0.98, true, 17);
    break_reciprocity(sys, 18);
    MatrixRows rows(sys.rows);
    const SparseMatrix F = to_matrix(sys.rows);
    const std::vector<Rgb> truth = direct_solve(sys.elements, rows);
    for (Method m : methods) {
        const SolveResult r = solve(sys.elements, F, settings_for(m, 1e-10));
        EXPECT_TRUE(r.converged);
        const double error = max_relative_error(r.radiance, truth);
        EXPECT_LT(error, 1e-5) << "method " << int(m);
        std::printf("stored, method %d: %d sweeps, %zu shots, max rel error %.3g\n", int(m), r.iterations, r.shots,
                    error);
    }
    const SolveResult reciprocal = solve(sys.elements, rows, settings_for(Method::Progressive, 1e-10));
    std::printf("reciprocity shooting on the same rows misses by %.3g (max rel)\n",
                max_relative_error(reciprocal.radiance, truth));
    EXPECT_GT(max_relative_error(reciprocal.radiance, truth), 1e-3);
}

TEST(Solver, ProgressiveResidualOnStoredColumnsIsExactFromTheFirstShot) {
    System sys = random_enclosure(50, 0.7, 0.95, true, 19);
    break_reciprocity(sys, 20);
    MatrixRows rows(sys.rows);
    const SparseMatrix F = to_matrix(sys.rows);
    for (int cap : {1, 3, 1000}) {
        const SolveResult r = solve(sys.elements, F, settings_for(Method::Progressive, 1e-6, cap));
        const double truth = relative_residual(sys.elements, rows, r.radiance);
        EXPECT_NEAR(r.residual, truth, 1e-9 * truth + 1e-12) << "cap " << cap;
        EXPECT_EQ(r.converged, cap == 1000);
    }
}

TEST(Solver, FurnaceClosedEnclosure) {
    // Rows summing to exactly 1 (up to float32), uniform E and rho: L = E / (1 - rho).
    System sys = random_enclosure(40, 1.0, 1.0, false, 3);
    const Rgb rho(0.5, 0.8, 0.9), E(1.0, 0.5, 0.25);
    for (std::size_t i = 0; i < sys.elements.size(); ++i) {
        sys.elements.reflectance[i] = rho;
        sys.elements.emission[i] = E;
    }
    MatrixRows rows(sys.rows);
    const Rgb expected = E / (1.0 - rho);
    for (Method m : methods) {
        const SolveResult r = solve(sys.elements, rows, settings_for(m, 1e-9));
        ASSERT_TRUE(r.converged);
        for (const Rgb& L : r.radiance)
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(L[c] / expected[c], 1.0, 1e-4) << "method " << int(m);
    }
}

TEST(Solver, ReturnedResidualIsTheTrueResidualOfTheReturnedRadiance) {
    const System sys = random_enclosure(50, 0.7, 0.95, true, 11);
    MatrixRows rows(sys.rows);
    for (Method m : {Method::GaussSeidel, Method::Jacobi}) {
        for (int cap : {3, 1000}) {  // stopped by the cap, and converged
            const SolveResult r = solve(sys.elements, rows, settings_for(m, 1e-6, cap));
            const double truth = relative_residual(sys.elements, rows, r.radiance);
            EXPECT_NEAR(r.residual, truth, 1e-12 + 1e-9 * truth) << "method " << int(m) << " cap " << cap;
            ASSERT_EQ(r.residual_history.size(), static_cast<std::size_t>(r.iterations));
            EXPECT_EQ(r.residual_history.back(), r.residual);
            EXPECT_EQ(r.converged, cap == 1000);
            if (cap == 3) EXPECT_EQ(r.iterations, 3);
        }
    }
    // Progressive: the reported value bounds the true residual from above.
    for (int cap : {1, 1000}) {
        const SolveResult r = solve(sys.elements, rows, settings_for(Method::Progressive, 1e-6, cap));
        const double truth = relative_residual(sys.elements, rows, r.radiance);
        EXPECT_GE(r.residual, truth * (1.0 - 1e-6)) << "cap " << cap;
        EXPECT_EQ(r.residual_history.back(), r.residual);
        EXPECT_EQ(r.converged, r.residual <= 1e-6);
        EXPECT_EQ(r.iterations, static_cast<int>((r.shots + sys.elements.size() - 1) / sys.elements.size()));
    }
}

TEST(Solver, ResidualHistoryDecreases) {
    const System sys = random_enclosure(50, 0.8, 0.99, false, 5);
    MatrixRows rows(sys.rows);
    for (Method m : methods) {
        const SolveResult r = solve(sys.elements, rows, settings_for(m, 1e-8));
        ASSERT_TRUE(r.converged);
        ASSERT_GE(r.residual_history.size(), 3u);
        for (std::size_t k = 1; k < r.residual_history.size(); ++k)
            EXPECT_LT(r.residual_history[k], r.residual_history[k - 1]) << "method " << int(m) << " sweep " << k;
    }
}

TEST(Solver, ZeroEmissionGivesZeros) {
    System sys = random_enclosure(20, 0.5, 0.9, false, 1);
    for (Rgb& E : sys.elements.emission) E = Rgb(0.0);
    MatrixRows rows(sys.rows);
    for (Method m : methods) {
        const SolveResult r = solve(sys.elements, rows, settings_for(m, 1e-6));
        EXPECT_TRUE(r.converged);
        EXPECT_EQ(r.residual, 0.0);
        EXPECT_EQ(r.iterations, 0);
        ASSERT_EQ(r.radiance.size(), sys.elements.size());
        for (const Rgb& L : r.radiance) EXPECT_EQ(L, Rgb(0.0));
    }
    EXPECT_EQ(rows.calls, 0u);
}

TEST(Solver, CancelThrowsAndProgressIsWellFormed) {
    const System sys = random_enclosure(200, 0.8, 0.99, false, 9);
    MatrixRows rows(sys.rows);
    for (Method m : methods) {
        int calls = 0;
        std::size_t last_done = 0;
        auto progress = [&](const Progress& p) {
            EXPECT_STREQ(p.phase, "solve");
            EXPECT_GT(p.done, last_done);
            EXPECT_LE(p.done, p.total);
            EXPECT_EQ(p.element_count, sys.elements.size());
            EXPECT_NE(p.radiance, nullptr);
            EXPECT_TRUE(std::isfinite(p.residual));
            last_done = p.done;
            return ++calls < 3;
        };
        EXPECT_THROW(solve(sys.elements, rows, settings_for(m, 1e-12), progress), Cancelled) << int(m);
        EXPECT_EQ(calls, 3);
    }
}

TEST(Solver, DivergenceIsReportedNotReturned) {
    // Rows summing to 1.3 with rho = 0.99: spectral radius about 1.29, every method grows.
    System sys = random_enclosure(30, 1.3, 1.3, false, 2);
    for (Rgb& rho : sys.elements.reflectance) rho = Rgb(0.99);
    MatrixRows rows(sys.rows);
    for (Method m : methods) {
        rows.calls = 0;
        try {
            solve(sys.elements, rows, settings_for(m, 1e-8, 100000));
            ADD_FAILURE() << "method " << int(m) << " returned";
        } catch (const Cancelled&) {
            ADD_FAILURE() << "cancelled";
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find("grew"), std::string::npos) << e.what();
        }
        // Caught by its growth within a few sweeps, long before it overflows.
        EXPECT_LT(rows.calls, 20 * sys.elements.size()) << "method " << int(m);
    }
}

TEST(Solver, NonFiniteResidualIsReportedNotReturned) {
    System sys = random_enclosure(10, 0.5, 0.9, false, 2);
    sys.rows[3].val[0] = std::numeric_limits<float>::infinity();
    MatrixRows rows(sys.rows);
    for (Method m : methods) {
        try {
            solve(sys.elements, rows, settings_for(m, 1e-8));
            ADD_FAILURE() << "method " << int(m) << " returned";
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find("not finite"), std::string::npos) << e.what();
        }
    }
}

TEST(Solver, AmbientOnlyInThePreview) {
    System sys = random_enclosure(100, 1.0, 1.0, false, 4);
    const Rgb rho(0.7), E(1.0);
    for (std::size_t i = 0; i < sys.elements.size(); ++i) {
        sys.elements.reflectance[i] = rho;
        sys.elements.emission[i] = i < 5 ? E * 20.0 : Rgb(0.0);
    }
    MatrixRows rows(sys.rows);
    const std::vector<Rgb> truth = direct_solve(sys.elements, rows);
    SolveSettings s = settings_for(Method::Progressive, 1e-6);
    const SolveResult plain = solve(sys.elements, rows, s);

    std::vector<double> error_with, error_without;
    for (bool ambient : {false, true}) {
        s.ambient = ambient;
        auto progress = [&](const Progress& p) {
            const std::vector<Rgb> preview(p.radiance, p.radiance + p.element_count);
            (ambient ? error_with : error_without).push_back(max_relative_error(preview, truth));
            return true;
        };
        const SolveResult r = solve(sys.elements, rows, s, progress);
        EXPECT_EQ(r.radiance, plain.radiance);  // the result never holds the ambient term
    }
    // Early on, the ambient term makes the preview much closer to the answer.
    ASSERT_GT(error_without.size(), 10u);
    EXPECT_LT(error_with[0], 0.5 * error_without[0]);
    EXPECT_LT(error_with[10], error_without[10]);
}

}  // namespace
}  // namespace radiosity
