// The condition number Newton names a singular tangent by (condition_estimate.hpp): the
// estimate of ||A^-1||_1 from solves against the exact one from a dense inverse, on matrices
// whose 1-norm and infinity-norm differ 45 times (a solve with A^T for one with A shows), a
// nearly singular one, and a permuted copy (the same number whatever the elimination order);
// and UMFPACK's figure from its factors of a CSR matrix.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <sundials/sundials_context.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "../../lib/solvers/condition_estimate.hpp"
#include "../../lib/solvers/umfpack_linear_solver.hpp"

using namespace perinom;

namespace {

/// ||A||_1 ||A^-1||_1 and its estimate through dense LU solves.
struct Figures {
  double exact, estimated;
};

Figures condition(const Eigen::MatrixXd& A) {
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(A);
  const Eigen::MatrixXd inverse = lu.inverse();
  const double norm = A.cwiseAbs().colwise().sum().maxCoeff();
  const auto solve = [&](std::vector<double>& b) {
    Eigen::Map<Eigen::VectorXd> v(b.data(), static_cast<Eigen::Index>(b.size()));
    v = lu.solve(Eigen::VectorXd(v));
  };
  const auto solve_transposed = [&](std::vector<double>& b) {
    Eigen::Map<Eigen::VectorXd> v(b.data(), static_cast<Eigen::Index>(b.size()));
    v = lu.transpose().solve(Eigen::VectorXd(v));
  };
  return {norm * inverse.cwiseAbs().colwise().sum().maxCoeff(),
          norm * detail::inverse_norm1_estimate(static_cast<std::size_t>(A.rows()), solve, solve_transposed)};
}

/// The identity with a first row of tens: ||A^-1||_1 = 11, ||A^-1||_inf = 491 (n = 50).
Eigen::MatrixXd row_of_tens(int n) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Identity(n, n);
  A.row(0).tail(n - 1).setConstant(10.0);
  return A;
}

/// A free-ended chain's stiffness (singular: the rigid translation) plus eps on the diagonal.
Eigen::MatrixXd nearly_free_chain(int n, double eps) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i + 1 < n; ++i) {
    A(i, i) += 1.0, A(i + 1, i + 1) += 1.0;
    A(i, i + 1) -= 1.0, A(i + 1, i) -= 1.0;
  }
  A.diagonal().array() += eps;
  return A;
}

SUNMatrix csr(SUNContext ctx, const Eigen::MatrixXd& dense) {
  const auto n = static_cast<sunindextype>(dense.rows());
  SUNMatrix A = SUNSparseMatrix(n, n, static_cast<sunindextype>((dense.array() != 0.0).count()), CSR_MAT, ctx);
  sunindextype k = 0;
  for (sunindextype i = 0; i < n; ++i) {
    SM_INDEXPTRS_S(A)[i] = k;
    for (sunindextype j = 0; j < n; ++j)
      if (dense(i, j) != 0.0) SM_INDEXVALS_S(A)[k] = j, SM_DATA_S(A)[k++] = dense(i, j);
  }
  SM_INDEXPTRS_S(A)[n] = k;
  return A;
}

}  // namespace

TEST_CASE("the condition estimate matches the exact 1-norm condition number, whatever the order", "[solvers][newton]") {
  const Figures tens = condition(row_of_tens(50));
  CHECK(tens.exact == Approx(11.0 * 11.0));  // ||A||_1 = 11: a transposed solve would make it 491^2
  CHECK(tens.estimated == Approx(tens.exact).epsilon(1e-12));

  const Figures chain = condition(nearly_free_chain(40, 1e-12));
  CHECK(chain.exact > 1e12);
  CHECK(chain.estimated <= chain.exact * (1.0 + 1e-6));
  CHECK(chain.estimated >= chain.exact / 3.0);

  // A random diagonally dominated matrix with rows scaled over six decades, and its copy under
  // a symmetric permutation (another elimination order): one condition number.
  const int n = 60;
  std::srand(7);
  Eigen::MatrixXd R = Eigen::MatrixXd::Random(n, n);
  R.diagonal().array() += 8.0;
  for (int i = 0; i < n; ++i) R.row(i) *= std::pow(10.0, 6.0 * i / (n - 1));
  Eigen::PermutationMatrix<Eigen::Dynamic> P(n);
  P.setIdentity();
  std::reverse(P.indices().data(), P.indices().data() + n);
  std::swap(P.indices()[3], P.indices()[40]);
  const Figures random = condition(R), permuted = condition(P * R * P.transpose());
  CHECK(random.estimated <= random.exact * (1.0 + 1e-9));
  CHECK(random.estimated >= random.exact / 3.0);
  CHECK(permuted.exact == Approx(random.exact).epsilon(1e-9));
  CHECK(permuted.estimated == Approx(random.estimated).epsilon(0.5));
}

TEST_CASE("UMFPACK's condition number is that of the CSR matrix it factored, infinite with a zero pivot",
          "[solvers][newton]") {
  SUNContext ctx = nullptr;
  REQUIRE(SUNContext_Create(nullptr, &ctx) == 0);
  SUNLinearSolver ls = detail::umfpack_linear_solver(ctx);
  const Eigen::MatrixXd tens = row_of_tens(50);
  SUNMatrix A = csr(ctx, tens);
  REQUIRE(SUNLinSolSetup(ls, A) == SUNLS_SUCCESS);
  CHECK(detail::umfpack_condition_number(ls, A) == Approx(condition(tens).exact).epsilon(1e-12));
  const Eigen::MatrixXd chain = nearly_free_chain(40, 1e-12);
  SUNMatrix C = csr(ctx, chain);
  REQUIRE(SUNLinSolSetup(ls, C) == SUNLS_SUCCESS);
  const double c = detail::umfpack_condition_number(ls, C);
  CHECK(c <= condition(chain).exact * (1.0 + 1e-6));
  CHECK(c >= condition(chain).exact / 3.0);
  Eigen::MatrixXd empty_row = tens;
  empty_row.row(49).setZero();
  SUNMatrix S = csr(ctx, empty_row);  // singular
  SUNLinSolSetup(ls, S);
  CHECK(std::isinf(detail::umfpack_condition_number(ls, S)));
  for (SUNMatrix m : {A, C, S}) SUNMatDestroy(m);
  SUNLinSolFree(ls);
  SUNContext_Free(&ctx);
}
