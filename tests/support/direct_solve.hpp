#pragma once
// Test support: solves the linear discrete system K u = f directly (Eigen SparseLU on the
// assembled tangent rows), an independent route to compare the explicit solvers with.
#include <Eigen/SparseLU>
#include <Eigen/SparseCore>
#include <vector>

#include "perinom/models/correspondence.hpp"
#include "perinom/models/loading.hpp"
#include "perinom/operators/tangent_rows.hpp"

namespace perinom::test {

/// u with u = u_bar on the constrained dofs and K u = f on the others (linear elasticity).
inline std::vector<double> direct_solve(const CorrespondenceModel& model, const Loading& loading) {
  const int d = model.dofs_per_particle();
  const std::size_t n = model.dofs();
  std::vector<char> fixed(n, 0);
  std::vector<double> ubar(n, 0.0);
  for (std::size_t k = 0; k < loading.fixed.size(); ++k) fixed[loading.fixed[k]] = 1, ubar[loading.fixed[k]] = loading.value[k];
  std::vector<double> C(d * d * d * d);
  model.material().tangent(C.data());
  const Surface& s = model.surface();
  const StrongRows strong{s.in_band.data(), s.normal_over_h.data()};
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
  for (std::size_t k = 0; k < n; ++k) rhs[k] = loading.force.empty() ? 0.0 : loading.force[k];
  std::vector<std::vector<Eigen::Triplet<double>>> rows(model.particles());
  for_each_tangent_row(
      model.G(), {C.data(), 0, model.volume().data()}, model.S(),
      [&](std::size_t i, const std::vector<ParticleId>& cols, const std::vector<double>& blocks) {
        for (std::size_t q = 0; q < cols.size(); ++q)
          for (int a = 0; a < d; ++a)
            for (int b = 0; b < d; ++b) {
              const std::size_t r = i * d + a, c = cols[q] * d + b;
              const double v = blocks[(q * d + a) * d + b];
              if (fixed[r]) continue;
              if (fixed[c]) rows[i].emplace_back(r, n, v * ubar[c]);  // moved to the right side
              else rows[i].emplace_back(r, c, v);
            }
      },
      model.formulation() == Formulation::classical ? nullptr : &strong);
  for (auto& r : rows)
    for (const auto& t : r) {
      if (t.col() == static_cast<Eigen::Index>(n)) rhs[t.row()] -= t.value();
      else triplets.push_back(t);
    }
  for (std::size_t k = 0; k < n; ++k)
    if (fixed[k]) triplets.emplace_back(k, k, 1.0), rhs[k] = ubar[k];
  Eigen::SparseMatrix<double> K(n, n);
  K.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(K);
  const Eigen::VectorXd u = lu.solve(rhs);
  return std::vector<double>(u.data(), u.data() + n);
}

}  // namespace perinom::test
