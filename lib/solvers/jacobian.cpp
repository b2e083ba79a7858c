#include "perinom/solvers/jacobian.hpp"

#include <algorithm>
#include <cmath>

namespace perinom {

std::size_t CsrMatrix::memory_bytes() const {
  return (row_ptr.size() + col.size()) * sizeof(std::int64_t) + val.size() * sizeof(double);
}

StaticSystem::StaticSystem(TangentModel& model, const Loading& loading)
    : model_(model), loading_(loading), constraint_of_(model.dofs(), -1), fint_(model.dofs()) {
  for (std::size_t k = 0; k < loading.fixed.size(); ++k) constraint_of_[loading.fixed[k]] = k;
  J_.rows = static_cast<std::int64_t>(model.dofs());
  fill(true);
}

void StaticSystem::fill(bool symbolic) {
  const int d = model_.dofs_per_particle();
  const std::size_t n = model_.particles();
  // Stiffness rows: one pass over the block rows, each particle's d rows written to their
  // own slots (the pattern pass counts first, so both passes write in place).
  std::vector<std::int64_t> count(n, 0);
  if (symbolic) {
    model_.visit_tangent_rows([&](std::size_t i, const std::vector<ParticleId>& cols, const std::vector<double>&) {
      count[i] = static_cast<std::int64_t>(cols.size());
    });
    J_.row_ptr.assign(J_.rows + 1, 0);
    for (std::size_t i = 0; i < n; ++i)
      for (int a = 0; a < d; ++a) {
        const std::int64_t r = i * d + a, k = constraint_of_[r];
        std::int64_t len = count[i] * d;
        if (k >= 0)
          len = 1 + (loading_.coupled_constraints() ? loading_.couplings[k + 1] - loading_.couplings[k] : 0);
        J_.row_ptr[r + 1] = J_.row_ptr[r] + len;
      }
    J_.col.assign(J_.row_ptr.back(), 0);
    J_.val.assign(J_.row_ptr.back(), 0.0);
  }
  double diag_max = 0.0;
  model_.visit_tangent_rows([&](std::size_t i, const std::vector<ParticleId>& cols, const std::vector<double>& blocks) {
    double local_max = 0.0;
    for (int a = 0; a < d; ++a) {
      const std::int64_t r = i * d + a;
      if (constraint_of_[r] >= 0) continue;
      std::int64_t slot = J_.row_ptr[r];
      for (std::size_t q = 0; q < cols.size(); ++q)
        for (int b = 0; b < d; ++b, ++slot) {
          J_.col[slot] = static_cast<std::int64_t>(cols[q]) * d + b;
          J_.val[slot] = blocks[(q * d + a) * d + b];
          if (cols[q] == static_cast<ParticleId>(i) && a == b) local_max = std::max(local_max, std::abs(J_.val[slot]));
        }
    }
#pragma omp critical(perinom_jacobian_kappa)
    diag_max = std::max(diag_max, local_max);
  });
  kappa_ = diag_max > 0.0 ? diag_max : 1.0;
  for (std::size_t k = 0; k < loading_.fixed.size(); ++k) {
    const std::int64_t r = loading_.fixed[k];
    std::int64_t slot = J_.row_ptr[r];
    J_.col[slot] = r;
    J_.val[slot++] = kappa_ / (loading_.coupled_constraints() ? loading_.scale[k] : 1.0);
    if (!loading_.coupled_constraints()) continue;
    for (Offset c = loading_.couplings[k]; c < loading_.couplings[k + 1]; ++c, ++slot) {
      J_.col[slot] = loading_.coupled[c];
      J_.val[slot] = kappa_ * loading_.coef[c];
    }
  }
  // Constraint rows must list their columns in order too (the diagonal first was a guess).
  for (std::size_t k = 0; k < loading_.fixed.size() && loading_.coupled_constraints(); ++k) {
    const std::int64_t r = loading_.fixed[k];
    std::vector<std::pair<std::int64_t, double>> row;
    for (std::int64_t s = J_.row_ptr[r]; s < J_.row_ptr[r + 1]; ++s) row.emplace_back(J_.col[s], J_.val[s]);
    std::sort(row.begin(), row.end());
    for (std::size_t m = 0; m < row.size(); ++m) J_.col[J_.row_ptr[r] + m] = row[m].first, J_.val[J_.row_ptr[r] + m] = row[m].second;
  }
}

void StaticSystem::assemble(const double* u) {
  // Linear models: the tangent does not depend on u (u may be null); plasticity: the
  // consistent tangents at u. The pattern is kept either way.
  if (u) model_.prepare_tangent(u);
  fill(false);
}

void StaticSystem::residual(const double* u, double s, double* R) {
  model_.follow_loads(loading_, s);
  model_.internal_force(u, R);
  if (loading_.has_force())
    for (std::size_t k = 0; k < dofs(); ++k) R[k] -= loading_.force_at(s, k);
  for (std::size_t k = 0; k < loading_.fixed.size(); ++k) {
    double v = u[loading_.fixed[k]];
    if (loading_.coupled_constraints()) {
      v /= loading_.scale[k];
      for (Offset c = loading_.couplings[k]; c < loading_.couplings[k + 1]; ++c) v += loading_.coef[c] * u[loading_.coupled[c]];
    }
    R[loading_.fixed[k]] = kappa_ * (v - loading_.target(s, k));
  }
}

double StaticSystem::load_norm(const double* u, double s) {
  model_.follow_loads(loading_, s);
  model_.internal_force(u, fint_.data());
  double reactions = 0.0;
  for (const auto dof : loading_.fixed) reactions += fint_[dof] * fint_[dof];
  return std::max(loading_.force_norm(s), std::sqrt(reactions));
}

}  // namespace perinom
