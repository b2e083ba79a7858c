#include "perinom/distributed/distributed_model.hpp"

#include <algorithm>
#include <numeric>

namespace perinom {

DistributedModel::DistributedModel(LocalModel& local, const LocalPart& part)
    : local_(local), part_(part), u_local_(local.dofs(), 0.0), f_local_(local.dofs(), 0.0) {
  local_.limit_rows(part.owned + part.near, part.owned);
  const std::vector<std::int64_t> ghosts(part.global.begin() + std::ptrdiff_t(part.owned), part.global.end());
  halo_ = std::make_unique<Halo>(part.owned, ghosts, local.dofs_per_particle(), u_local_.data());
}

const std::vector<double>& DistributedModel::local_state(const double* u) const {
  std::copy(u, u + dofs(), u_local_.begin());
  halo_->update();
  return u_local_;
}

void DistributedModel::internal_force(const double* u, double* f) {
  local_.internal_force(local_state(u).data(), f_local_.data());
  std::copy(f_local_.begin(), f_local_.begin() + std::ptrdiff_t(dofs()), f);
}

double DistributedModel::energy(const double* u) { return local_.energy(local_state(u).data()); }

std::vector<double> DistributedModel::lumped_mass() const {
  std::vector<double> m = local_.lumped_mass();
  m.resize(dofs());
  return m;
}

std::vector<double> DistributedModel::stiffness_row_sums() const {
  // The owned rows read the near ghosts' rows of G, which their full families make exact.
  return local_.stiffness_row_sums(owned_rows());
}

std::vector<ParticleId> DistributedModel::owned_rows() const {
  std::vector<ParticleId> rows(part_.owned);
  std::iota(rows.begin(), rows.end(), ParticleId(0));
  return rows;
}

void DistributedModel::visit_tangent_rows(const TangentRowVisitor& visit) const {
  local_.visit_tangent_rows(owned_rows(), visit);
}

std::vector<std::pair<std::string, std::size_t>> DistributedModel::memory() const {
  auto m = local_.memory();
  m.emplace_back("local state and force (owned and ghosts)", (u_local_.size() + f_local_.size()) * sizeof(double));
  return m;
}

std::vector<OutputField> DistributedModel::output_fields(const double* u, bool probe_fields, bool gradients) const {
  std::vector<OutputField> fields = local_.output_fields(local_state(u).data(), probe_fields, gradients);
  for (auto& f : fields) f.values.resize(part_.owned * std::size_t(f.components));
  return fields;
}

std::vector<double> DistributedModel::stress_measure(const double* u) const {
  std::vector<double> s = local_.stress_measure(local_state(u).data());
  s.resize(s.size() / local_.particles() * part_.owned);
  return s;
}

}  // namespace perinom
