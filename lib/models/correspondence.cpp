#include "perinom/models/correspondence.hpp"

#include "perinom/operators/bond_weights.hpp"
#include "perinom/operators/stabilization.hpp"
#include "perinom/operators/tangent_rows.hpp"

namespace perinom {

CorrespondenceModel::CorrespondenceModel(const PointCloud& cloud, const Families& families,
                                         const LinearElastic& material,
                                         const CorrespondenceOptions& options)
    : dim_(cloud.dim), material_(material), volume_(cloud.volume) {
  const BondWeights weights = bond_weights(cloud, families, options.influence);
  G_ = GradientOperator(cloud, families, weights);
  if (options.stabilization > 0.0) {
    const auto c = stabilization_coefficients(weights, dim_, options.stabilization, material.mu());
    S_ = assemble_stabilization(cloud, families, weights, G_, c);
  }
  H_.resize(particles() * dim_ * dim_);
  Q_.resize(particles() * dim_ * dim_);
}

void CorrespondenceModel::gradient(const double* u, double* H) const { G_.apply(u, dim_, H); }

void CorrespondenceModel::internal_force(const double* u, double* f) {
  const int d2 = dim_ * dim_;
  const std::size_t n = particles();
  G_.apply(u, dim_, H_.data());
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    double* q = Q_.data() + i * d2;
    material_.stress(H_.data() + i * d2, q);
    for (int k = 0; k < d2; ++k) q[k] *= volume_[i];
  }
  G_.apply_transpose(Q_.data(), dim_, f);
  if (S_) S_->apply_add(u, dim_, f);
}

double CorrespondenceModel::energy(const double* u) {
  const int d2 = dim_ * dim_;
  const std::size_t n = particles();
  G_.apply(u, dim_, H_.data());
  double w = 0.0;
#pragma omp parallel for reduction(+ : w) schedule(static)
  for (std::size_t i = 0; i < n; ++i) w += volume_[i] * material_.energy(H_.data() + i * d2);
  if (S_) {
    std::vector<double> su(n * dim_, 0.0);
    S_->apply_add(u, dim_, su.data());
    for (std::size_t k = 0; k < su.size(); ++k) w += 0.5 * u[k] * su[k];
  }
  return w;
}

std::vector<double> CorrespondenceModel::lumped_mass() const {
  std::vector<double> m(particles() * dim_);
  for (std::size_t i = 0; i < particles(); ++i)
    for (int a = 0; a < dim_; ++a) m[i * dim_ + a] = material_.density * volume_[i];
  return m;
}

std::vector<double> CorrespondenceModel::stiffness_row_sums() const {
  std::vector<double> C(dim_ * dim_ * dim_ * dim_);
  material_.tangent(C.data());
  return tangent_row_abs_sums(G_, PointwiseTangent{C.data(), 0, volume_.data()}, S());
}

std::vector<std::pair<std::string, std::size_t>> CorrespondenceModel::memory() const {
  std::vector<std::pair<std::string, std::size_t>> m;
  m.emplace_back("gradient operator G and G^T", G_.memory_bytes());
  if (S_) m.emplace_back("stabilization S", S_->memory_bytes());
  m.emplace_back("workspaces (grad u, V.P)", (H_.size() + Q_.size()) * sizeof(double));
  return m;
}

void CorrespondenceModel::stress3(const double* u, std::vector<double>& sigma) const {
  const int d2 = dim_ * dim_;
  std::vector<double> H(particles() * d2);
  gradient(u, H.data());
  sigma.resize(particles() * 9);
  for (std::size_t i = 0; i < particles(); ++i)
    material_.stress3(H.data() + i * d2, sigma.data() + i * 9);
}

}  // namespace perinom
