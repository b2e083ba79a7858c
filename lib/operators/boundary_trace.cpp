#include "perinom/operators/boundary_trace.hpp"

namespace perinom {

BoundaryTrace::BoundaryTrace(BoundaryFacets facets, const PointCloud& cloud, const NonlocalOperator& G)
    : facets_(std::move(facets)) {
  const int d = cloud.dim;
  for (std::size_t k = 0; k < facets_.size(); ++k) {
    const std::size_t p = facets_.particle[k];
    double r[3] = {0, 0, 0};
    for (int a = 0; a < d; ++a) r[a] = facets_.centroid[k * d + a] - cloud.x[p * d + a];
    double self = 1.0;
    G.visit_row(p, [&](ParticleId j, const double* g) {
      if (static_cast<std::size_t>(j) == p) return;  // the diagonal: self, below
      double c = 0.0;
      for (int a = 0; a < d; ++a) c += g[a] * r[a];
      cols_.push_back(j);
      coef_.push_back(c);
      self -= c;
    });
    cols_.push_back(static_cast<ParticleId>(p));
    coef_.push_back(self);
    offsets_.push_back(static_cast<Offset>(cols_.size()));
  }
}

std::vector<double> BoundaryTrace::column_measure(std::size_t particles) const {
  const int d = facets_.dim;
  std::vector<double> c(particles * d, 0.0);
  for (std::size_t k = 0; k < facets_.size(); ++k)
    for (std::size_t e = row_begin(k); e < row_end(k); ++e)
      for (int b = 0; b < d; ++b) c[cols_[e] * d + b] += facets_.area[k] * facets_.normal[k * d + b] * coef_[e];
  return c;
}

void BoundaryTrace::add_traction(std::size_t k, const double* t, double* f) const {
  const int d = facets_.dim;
  for (std::size_t e = row_begin(k); e < row_end(k); ++e)
    for (int a = 0; a < d; ++a) f[cols_[e] * d + a] += facets_.area[k] * t[a] * coef_[e];
}

std::size_t BoundaryTrace::memory_bytes() const {
  return offsets_.size() * sizeof(Offset) + cols_.size() * (sizeof(ParticleId) + sizeof(double)) +
         (facets_.area.size() + facets_.normal.size() + facets_.centroid.size()) * sizeof(double) +
         facets_.particle.size() * (sizeof(ParticleId) + sizeof(int));
}

}  // namespace perinom
