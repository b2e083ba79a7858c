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

/// u with the constraints of `loading` (on the particle, or face-located through their
/// couplings) and K u = f on the other dofs (linear elasticity).
inline std::vector<double> direct_solve(const CorrespondenceModel& model, const Loading& loading) {
  const int d = model.dofs_per_particle();
  const std::size_t n = model.dofs();
  std::vector<char> fixed(n, 0);
  for (const auto dof : loading.fixed) fixed[dof] = 1;
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
              if (!fixed[r]) rows[i].emplace_back(r, c, v);
            }
      },
      model.formulation() == Formulation::classical ? nullptr : &strong);
  for (auto& r : rows) triplets.insert(triplets.end(), r.begin(), r.end());
  // Constraint rows kappa (u_i / scale + sum_c coef_c u_c) = kappa u_bar, kappa the largest
  // stiffness diagonal so that the rows are scaled alike (SparseLU pivots by magnitude).
  double kappa = 0.0;
  for (const auto& t : triplets)
    if (t.row() == t.col()) kappa = std::max(kappa, std::abs(t.value()));
  for (std::size_t k = 0; k < loading.fixed.size(); ++k) {
    const auto dof = loading.fixed[k];
    rhs[dof] = kappa * loading.value[k];
    if (!loading.coupled_constraints()) {
      triplets.emplace_back(dof, dof, kappa);
      continue;
    }
    triplets.emplace_back(dof, dof, kappa / loading.scale[k]);
    for (Offset c = loading.couplings[k]; c < loading.couplings[k + 1]; ++c)
      triplets.emplace_back(dof, loading.coupled[c], kappa * loading.coef[c]);
  }
  Eigen::SparseMatrix<double> K(n, n);
  K.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(K);
  const Eigen::VectorXd u = lu.solve(rhs);
  return std::vector<double>(u.data(), u.data() + n);
}

}  // namespace perinom::test
