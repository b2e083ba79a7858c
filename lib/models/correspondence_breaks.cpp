// Breaking bonds in a correspondence model: the refresh of the rows they touch, and the
// update of a force and energy on those rows only (CorrespondenceModel::break_bonds).
#include <algorithm>
#include <stdexcept>
#include <string>

#include "perinom/models/correspondence.hpp"
#include "perinom/operators/hourglass_energy.hpp"

namespace perinom {

void CorrespondenceModel::check_breakable(const std::vector<std::pair<ParticleId, ParticleId>>& bonds) const {
  for (const auto& [i, j] : bonds)
    if (static_cast<std::size_t>(i) >= particles() || static_cast<std::size_t>(j) >= particles())
      throw std::out_of_range("break_bonds: bond (" + std::to_string(i) + ", " + std::to_string(j) +
                              ") names a particle beyond the " + std::to_string(particles()) + " of the cloud");
  // A pair that is no bond breaks nothing: a caller's mix-up of ids, not a crack. (A bond
  // broken already, or present one way only in k-nearest families, is still a bond.)
  for (const auto& [i, j] : bonds)
    if (i == j || (graph_->find(i, j) < 0 && graph_->find(j, i) < 0))
      throw std::invalid_argument("break_bonds: (" + std::to_string(i) + ", " + std::to_string(j) +
                                  ") is not a bond of the families");
  if (formulation_ == Formulation::consistent)
    throw std::logic_error("break_bonds: the consistent formulation's G~ comes from a global correction and "
                           "cannot be refreshed row by row");
  if (S_ && !S_->refreshable())
    throw std::logic_error("break_bonds: " + S_->name() + " is stored without the operator it came from "
                           "(with operator order 2, stabilization_storage matrix_free keeps it)");
}

BondBreaks CorrespondenceModel::break_bonds(const std::vector<std::pair<ParticleId, ParticleId>>& bonds) {
  check_breakable(bonds);
  BondBreaks out;
  out.rows = graph_->rows_touched(bonds);
  std::vector<std::pair<ParticleId, ParticleId>> died;  // they soften (soften_broken_bonds)
  auto change = [&] {
    graph_->begin_event();
    for (const auto& [i, j] : bonds)
      if (graph_->break_bond(i, j)) {
        ++out.broken;
        if (cohesive_) died.emplace_back(i, j);
      }
    G_.refresh_rows(out.rows);
  };
  if (S_) S_->refresh_rows(out.rows, change);
  else change();
  if (cohesive_) cohesive_->add(died);
  out.detached = G_.detached();
  return out;
}

double CorrespondenceModel::row_share(std::size_t i, const double* u, double sign, double* f) {
  const int d = dim_, d2 = d * d;
  // H_i = sum_j (u_j - u_i) g_ij from row i as stored (the first visit is the diagonal).
  double* H = H_.data() + i * d2;
  std::fill(H, H + d2, 0.0);
  bool diagonal = true;
  G_.visit_row(i, [&](ParticleId j, const double* a) {
    if (diagonal) return void(diagonal = false);
    for (int c = 0; c < d; ++c)
      for (int b = 0; b < d; ++b) H[c * d + b] += (u[j * d + c] - u[i * d + c]) * a[b];
  });
  // V_i psi(H_i), then its derivative G_i^T (V_i P_i); Q_ is scratch (psi at [i], P at row i).
  law_->energies(i, i + 1, H_.data(), Q_.data());
  double share = volume_[i] * Q_[i];
  law_->stresses(i, i + 1, H_.data(), Q_.data());
  const double* P = Q_.data() + i * d2;
  const double vs = sign * volume_[i];
  G_.visit_row(i, [&](ParticleId j, const double* a) {
    for (int c = 0; c < d; ++c) {
      double t = 0.0;
      for (int b = 0; b < d; ++b) t += P[c * d + b] * a[b];
      f[j * d + c] += vs * t;
    }
  });
  if (S_) share += volume_[i] * hourglass_row(G_, u, H_.data(), i, modulus_, volume_[i], sign, f);
  return share;
}

BondBreaks CorrespondenceModel::cut_bonds(const std::vector<std::pair<ParticleId, ParticleId>>& bonds) {
  if (cohesive_) throw std::logic_error("cut_bonds: the body is cut before its broken bonds soften");
  BondBreaks out = break_bonds(bonds);
  graph_->settle_events();
  return out;
}

BondBreaks CorrespondenceModel::break_bonds(const std::vector<std::pair<ParticleId, ParticleId>>& bonds,
                                            const double* u, double* f) {
  const bool by_rows = formulation_ == Formulation::classical && order_ == 1 &&
                       G_.precision() == WeightPrecision::float64 && !(follower_ && follower_->active());
  if (!by_rows) {
    const double before = energy(u);
    BondBreaks out = break_bonds(bonds);
    out.released = before - energy(u);
    internal_force(u, f);
    return out;
  }
  check_breakable(bonds);  // before f changes
  double before = 0.0, after = 0.0;
  for (const ParticleId i : graph_->rows_touched(bonds)) before += row_share(i, u, -1.0, f);
  const std::size_t softening = cohesive_ ? cohesive_->size() : 0;
  BondBreaks out = break_bonds(bonds);  // refreshes the same rows
  for (const ParticleId i : out.rows) after += row_share(i, u, 1.0, f);
  if (cohesive_) after += cohesive_->add_force(u, f, softening);  // the bonds that now soften
  out.released = before - after;
  return out;
}

}  // namespace perinom
