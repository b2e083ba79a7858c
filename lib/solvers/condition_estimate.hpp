#pragma once
/// @file The 1-norm condition number of a factored matrix, estimated from a few solves with
/// its factors (Hager's method with Higham's safeguard, as LAPACK's xLACN2 and MATLAB's
/// condest). Unlike the pivot ratio min |U_ii| / max |U_ii|, which is a property of the
/// elimination order (a column collapsing past its limit load: 1e-13 under one order, not
/// under another), it estimates ||A||_1 ||A^-1||_1, a property of the matrix: within a small
/// factor of the truth, whatever the order, usually exact.
#include <cstdint>
#include <functional>
#include <vector>

namespace perinom::detail {

/// Overwrites its argument b with x solving A x = b (or A^T x = b).
using FactorSolve = std::function<void(std::vector<double>&)>;

/// An estimate of ||A^-1||_1 (a lower bound, usually exact) from at most 6 solves with A and
/// 4 with A^T; infinite when a solve is (a zero pivot). n: A's size.
double inverse_norm1_estimate(std::size_t n, const FactorSolve& solve, const FactorSolve& solve_transposed);

/// ||A||_1 (the largest column sum of |a_ij|) of an n x n matrix in compressed rows.
double csr_norm1(std::int64_t n, const std::int64_t* row_ptr, const std::int64_t* col, const double* val);

}  // namespace perinom::detail
