#include "perinom/solvers/jacobian.hpp"

#include <algorithm>
#include <cmath>

namespace perinom {

std::size_t CsrMatrix::memory_bytes() const {
  return (row_ptr.size() + col.size()) * sizeof(std::int64_t) + val.size() * sizeof(double);
}

StaticSystem::StaticSystem(TangentModel& model, const Loading& loading)
    : model_(model), loading_(loading), constraint_of_(model.dofs(), -1), n_(model.dofs()), fint_(model.dofs()) {
  for (std::size_t k = 0; k < loading.fixed.size(); ++k) constraint_of_[loading.fixed[k]] = k;
  if (loading.galerkin()) {
    m_ = loading.fixed.size();
    std::vector<std::vector<std::pair<std::int64_t, double>>> et(n_);
    for (std::size_t k = 0; k < m_; ++k) {
      et[loading.fixed[k]].emplace_back(k, 1.0 / loading.scale[k]);
      for (Offset c = loading.couplings[k]; c < loading.couplings[k + 1]; ++c)
        et[loading.coupled[c]].emplace_back(k, loading.coef[c]);
    }
    et_ptr_.assign(1, 0);
    for (auto& row : et) {
      std::sort(row.begin(), row.end());
      for (const auto& [k, v] : row) et_k_.push_back(k), et_val_.push_back(v);
      et_ptr_.push_back(static_cast<std::int64_t>(et_k_.size()));
    }
  }
  J_.rows = static_cast<std::int64_t>(n_ + m_);
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
        const std::int64_t r = i * d + a;
        std::int64_t len = count[i] * d;
        const std::int64_t k = constraint_of_[r];
        if (m_ > 0) len += et_ptr_[r + 1] - et_ptr_[r];  // the multipliers' columns
        else if (k >= 0) len = 1 + (loading_.coupled_constraints() ? loading_.couplings[k + 1] - loading_.couplings[k] : 0);
        J_.row_ptr[r + 1] = J_.row_ptr[r] + len;
      }
    for (std::size_t k = 0; k < m_; ++k)
      J_.row_ptr[n_ + k + 1] = J_.row_ptr[n_ + k] + 1 + (loading_.couplings[k + 1] - loading_.couplings[k]);
    J_.col.assign(J_.row_ptr.back(), 0);
    J_.val.assign(J_.row_ptr.back(), 0.0);
  }
  double diag_max = 0.0;
  model_.visit_tangent_rows([&](std::size_t i, const std::vector<ParticleId>& cols, const std::vector<double>& blocks) {
    double local_max = 0.0;
    for (int a = 0; a < d; ++a) {
      const std::int64_t r = i * d + a;
      if (m_ == 0 && constraint_of_[r] >= 0) continue;
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
  // kappa is fixed at the first fill: the residual's multiplier terms kappa E^T y would
  // otherwise jump when a plastic tangent changes it, and the line search would compare
  // residuals of two different systems.
  if (symbolic) kappa_ = diag_max > 0.0 ? diag_max : 1.0;
  // Collocated constraints: row fixed[k] is kappa E_k (kappa at the dof without couplings).
  std::vector<std::pair<std::int64_t, double>> row;
  for (std::size_t k = 0; k < loading_.fixed.size() && m_ == 0; ++k) {
    const std::int64_t r = loading_.fixed[k];
    row.assign(1, {r, loading_.coupled_constraints() ? 1.0 / loading_.scale[k] : 1.0});
    for (Offset c = loading_.coupled_constraints() ? loading_.couplings[k] : 0;
         loading_.coupled_constraints() && c < loading_.couplings[k + 1]; ++c)
      row.emplace_back(loading_.coupled[c], loading_.coef[c]);
    std::sort(row.begin(), row.end());
    for (std::size_t q = 0; q < row.size(); ++q) {
      J_.col[J_.row_ptr[r] + q] = row[q].first;
      J_.val[J_.row_ptr[r] + q] = kappa_ * row[q].second;
    }
  }
  if (m_ == 0) return;
  // The multipliers' columns close each stiffness row (their indices follow every dof's).
  for (std::size_t r = 0; r < n_; ++r) {
    std::int64_t slot = J_.row_ptr[r + 1] - (et_ptr_[r + 1] - et_ptr_[r]);
    for (std::int64_t e = et_ptr_[r]; e < et_ptr_[r + 1]; ++e, ++slot) {
      J_.col[slot] = static_cast<std::int64_t>(n_) + et_k_[e];
      J_.val[slot] = kappa_ * et_val_[e];
    }
  }
  // Constraint rows kappa E_l, columns in order.
  for (std::size_t k = 0; k < m_; ++k) {
    row.assign(1, {loading_.fixed[k], 1.0 / loading_.scale[k]});
    for (Offset c = loading_.couplings[k]; c < loading_.couplings[k + 1]; ++c) row.emplace_back(loading_.coupled[c], loading_.coef[c]);
    std::sort(row.begin(), row.end());
    for (std::size_t q = 0; q < row.size(); ++q) {
      J_.col[J_.row_ptr[n_ + k] + q] = row[q].first;
      J_.val[J_.row_ptr[n_ + k] + q] = kappa_ * row[q].second;
    }
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
    for (std::size_t k = 0; k < n_; ++k) R[k] -= loading_.force_at(s, k);
  const double* y = u + n_;
  for (std::size_t r = 0; r < n_ && m_ > 0; ++r)
    for (std::int64_t e = et_ptr_[r]; e < et_ptr_[r + 1]; ++e) R[r] += kappa_ * et_val_[e] * y[et_k_[e]];
  // The constraint rows: the multipliers' own, or (collocated) the constrained dofs'.
  for (std::size_t k = 0; k < loading_.fixed.size(); ++k) {
    double v = u[loading_.fixed[k]];
    if (loading_.coupled_constraints()) {
      v /= loading_.scale[k];
      for (Offset c = loading_.couplings[k]; c < loading_.couplings[k + 1]; ++c) v += loading_.coef[c] * u[loading_.coupled[c]];
    }
    R[m_ > 0 ? n_ + k : loading_.fixed[k]] = kappa_ * (v - loading_.target(s, k));
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
