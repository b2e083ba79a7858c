#include "inertia.hpp"

#include <Eigen/Dense>
#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>

#include "perinom/core/error.hpp"

namespace perinom {
namespace {

using Sparse = Eigen::SparseMatrix<double>;
using Vector = Eigen::VectorXd;

/// Lanczos in the B inner product (B = M for x <- M^-1 K x, B = M for x <- K^-1 M x, both
/// self-adjoint in it), with full reorthogonalization, for up to `steps` steps from a fixed
/// start: the smallest and largest Ritz values, which approach the extreme eigenvalues from
/// inside (exactly at `steps` >= n).
template <class Apply>
std::pair<double, double> lanczos_extremes(const Sparse& B, Apply&& apply, int steps) {
  const Eigen::Index n = B.rows();
  const int k_max = static_cast<int>(std::min<Eigen::Index>(steps, n));
  Eigen::MatrixXd V(n, k_max), BV(n, k_max);
  Vector alpha(k_max), beta(k_max);
  Vector v(n);
  unsigned state = 12345u;  // a fixed pseudo-random start: every mode in it
  for (Eigen::Index i = 0; i < n; ++i) {
    state = state * 1664525u + 1013904223u;
    v[i] = double(state >> 8) / double(1u << 24) - 0.5;
  }
  v /= std::sqrt(v.dot(B * v));
  int k = 0;
  for (; k < k_max; ++k) {
    V.col(k) = v;
    BV.col(k) = B * v;
    Vector w = apply(v);
    alpha[k] = BV.col(k).dot(w);
    // Full reorthogonalization (twice) against every Lanczos vector so far.
    for (int pass = 0; pass < 2; ++pass) w -= V.leftCols(k + 1) * (BV.leftCols(k + 1).transpose() * w);
    const double b = std::sqrt(std::max(w.dot(B * w), 0.0));
    beta[k] = b;
    if (k + 1 == k_max || !(b > 1e-14 * std::abs(alpha[k]))) {
      ++k;
      break;
    }
    v = w / b;
  }
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(k, k);
  for (int i = 0; i < k; ++i) {
    T(i, i) = alpha[i];
    if (i + 1 < k) T(i, i + 1) = T(i + 1, i) = beta[i];
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(T, Eigen::EigenvaluesOnly);
  return {eig.eigenvalues().minCoeff(), eig.eigenvalues().maxCoeff()};
}

}  // namespace

PencilInertia pencil_inertia(const Sparse& K, const Sparse& M, int steps) {
  PencilInertia out;
  if (K.rows() == 0) return out;
  Eigen::SimplicialLLT<Sparse, Eigen::Lower> mass(M);
  if (mass.info() != Eigen::Success) throw SolveError("stability check: the reduced mass is not positive definite");
  // A supernodal Cholesky succeeds exactly when K is positive definite: no negative and no
  // zero eigenvalue. Otherwise the simplicial LDL^T (slower: no supernodes) counts them.
  Eigen::CholmodSupernodalLLT<Sparse, Eigen::Lower> llt;
  llt.cholmod().print = 0;  // "not positive definite" is an answer here, not a warning
  llt.compute(K);
  std::function<Vector(const Vector&)> solve_K;
  Eigen::SimplicialLDLT<Sparse, Eigen::Lower> ldlt;
  if (llt.info() == Eigen::Success) {
    out.cholesky = true;
    solve_K = [&](const Vector& b) { return Vector(llt.solve(b)); };
  } else {
    ldlt.compute(K);  // AMD ordering
    if (ldlt.info() != Eigen::Success) throw SolveError("stability check: the sparse LDL^T of the stiffness failed");
    // A rigid mode the supports leave free has a pivot that is rounding, of either sign: a
    // free 2-D body read "2 negative" and UNSTABLE beside a positive smallest eigenvalue.
    const Vector D = ldlt.vectorD();
    const double rounding = kZeroPivot * D.cwiseAbs().maxCoeff();
    for (Eigen::Index k = 0; k < D.size(); ++k) out.negative += D[k] < -rounding, out.zero += std::abs(D[k]) <= rounding;
    solve_K = [&](const Vector& b) { return Vector(ldlt.solve(b)); };
  }
  // x <- M^-1 K x: the largest eigenvalue, and the most negative one when there is one.
  const auto [low, high] = lanczos_extremes(M, [&](const Vector& x) { return Vector(mass.solve(K * x)); }, steps);
  out.max_lambda = std::max(std::abs(low), std::abs(high));
  if (out.negative > 0) out.min_lambda = low;
  // Positive definite: the smallest by shift-invert, x <- K^-1 M x, whose largest is 1 / lambda_min.
  else if (out.zero == 0)
    out.min_lambda = 1.0 / lanczos_extremes(M, [&](const Vector& x) { return solve_K(M * x); }, steps).second;
  return out;
}

}  // namespace perinom
