#pragma once
// Test support: solves the linear static problem R(u) = 0 with Eigen's SparseLU on the
// assembled Jacobian, a solver independent of KLU/KINSOL to compare ADR and Newton with.
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <vector>

#include "perinom/models/correspondence.hpp"
#include "perinom/models/loading.hpp"
#include "perinom/solvers/jacobian.hpp"

namespace perinom::test {

/// u with R(u) = 0 at full load (constraints on the particle or face-located). The problem
/// is linear, so R(u) = J u + R(0) and u = -J^-1 R(0).
inline std::vector<double> direct_solve(CorrespondenceModel& model, const Loading& loading) {
  StaticSystem system(model, loading);
  const std::size_t n = system.dofs();
  const CsrMatrix& J = system.jacobian();
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(J.col.size());
  for (std::int64_t r = 0; r < J.rows; ++r)
    for (std::int64_t s = J.row_ptr[r]; s < J.row_ptr[r + 1]; ++s) triplets.emplace_back(r, J.col[s], J.val[s]);
  Eigen::SparseMatrix<double> K(n, n);
  K.setFromTriplets(triplets.begin(), triplets.end());
  std::vector<double> zero(n, 0.0), R0(n);
  system.residual(zero.data(), 1.0, R0.data());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(K);
  const Eigen::VectorXd u = lu.solve(-Eigen::Map<const Eigen::VectorXd>(R0.data(), n));
  return std::vector<double>(u.data(), u.data() + model.dofs());  // without the multipliers
}

}  // namespace perinom::test
