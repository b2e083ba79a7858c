#pragma once
/// @file The spectrum of a symmetric pencil (K, M) without a dense solve: Sylvester's inertia
/// from a sparse LDL^T of K, and the extreme eigenvalues by Lanczos iterations.
///
/// For K symmetric and M symmetric positive definite, the eigenvalues of M^-1 K are real, and
/// as many are negative as K has negative pivots in K = P^T L D L^T P (K and
/// M^-1/2 K M^-1/2 are congruent). This answers "is the discrete problem stable?" for any
/// size a sparse factorization fits in memory. A positive definite K is recognized by a
/// supernodal Cholesky (CHOLMOD) that succeeds; only when it fails does the simplicial LDL^T
/// count the negative and zero pivots.
#include <Eigen/SparseCore>

namespace perinom {

/// A pivot of K's LDL^T within this fraction of the largest is zero (rounding, either sign).
inline constexpr double kZeroPivot = 1e-10;

struct PencilInertia {
  long negative = 0;      ///< negative pivots of K (below -kZeroPivot of the largest): eigenvalues of M^-1 K below zero
  long zero = 0;          ///< pivots within kZeroPivot of the largest (K singular: a rigid mode left free)
  bool cholesky = false;  ///< decided by a successful supernodal Cholesky (K positive definite)
  double min_lambda = 0;  ///< the smallest eigenvalue of M^-1 K (1/s^2): shift-invert Lanczos when
                          ///< none is negative, else Lanczos on M^-1 K (its lowest Ritz value)
  double max_lambda = 0;  ///< the largest |eigenvalue| (Lanczos; 1/s^2)
};

/// K and M: the reduced stiffness and mass (n x n, symmetric; M positive definite). The
/// extreme eigenvalues come from `steps` Lanczos steps with full reorthogonalization (exact
/// when steps >= n; from inside otherwise: the largest a little low, the smallest positive one
/// converges fast under shift-invert). Throws SolveError when K or M cannot be factored.
PencilInertia pencil_inertia(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                             int steps = 150);

}  // namespace perinom
