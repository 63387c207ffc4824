/// @file dense_solve.h
/// @brief The solver tests' independent truth: a dense direct solve of the radiosity system.
#pragma once

#include "common/sparse.h"
#include "geometry/scene.h"

#include <vector>

namespace radiosity::test {

using DenseMatrix = std::vector<std::vector<double>>;

/// Dense F from a stored matrix.
DenseMatrix dense(const SparseMatrix& m);

/// (I - rho F) L = E per channel by Gaussian elimination with partial pivoting.
std::vector<Rgb> direct_solve(const Elements& e, const DenseMatrix& F);

/// max_i,c |a - b| / max_i,c |b|
double max_relative_error(const std::vector<Rgb>& a, const std::vector<Rgb>& b);

}  // namespace radiosity::test
