#pragma once
/// @file Values on the boundary facets, reconstructed from the particles: the trace that
/// places loads, face constraints and the boundary measure of the consistent formulation
/// at the surface itself rather than on the outer particle layer.
#include <cstddef>
#include <vector>

#include "perinom/core/types.hpp"
#include "perinom/geometry/boundary_facets.hpp"
#include "perinom/geometry/point_cloud.hpp"
#include "perinom/operators/nonlocal_operator.hpp"

namespace perinom {

/// Row k of the trace E gives a field's value at facet k's centroid y_k from its owner p:
///   (E u)_k = u_p + (grad u)_p . (y_k - x_p) = sum_j E_kj u_j,  j in {p} + H_p,
/// exact for every field G differentiates exactly (linear for the first-order G).
class BoundaryTrace {
 public:
  BoundaryTrace() = default;
  /// E from the facets and a gradient operator (its stored weights).
  BoundaryTrace(BoundaryFacets facets, const PointCloud& cloud, const NonlocalOperator& G);

  const BoundaryFacets& facets() const { return facets_; }
  bool empty() const { return facets_.empty(); }

  /// The boundary measure of every particle's shape function, c[j*d + b] =
  /// sum_k A_k n_k[b] E_kj (m^2): the right-hand side of the discrete divergence theorem.
  std::vector<double> column_measure(std::size_t particles) const;
  /// f[j*d + a] += A_k t[a] E_kj: the work-consistent nodal forces of a traction t (Pa, d
  /// values) on facet k.
  void add_traction(std::size_t k, const double* t, double* f) const;
  /// Row k: its columns and coefficients (for face constraints).
  std::size_t row_begin(std::size_t k) const { return static_cast<std::size_t>(offsets_[k]); }
  std::size_t row_end(std::size_t k) const { return static_cast<std::size_t>(offsets_[k + 1]); }
  ParticleId col(std::size_t e) const { return cols_[e]; }
  double coef(std::size_t e) const { return coef_[e]; }

  std::size_t memory_bytes() const;

 private:
  BoundaryFacets facets_;
  std::vector<Offset> offsets_{0};
  std::vector<ParticleId> cols_;
  std::vector<double> coef_;
};

}  // namespace perinom
