#pragma once
/// @file The body's boundary as facets owned by particles: the surface a variationally
/// consistent weak form integrates over (docs/theory.md, "consistent formulation").
#include <vector>

#include "perinom/core/types.hpp"
#include "perinom/geometry/lattice.hpp"

namespace perinom {

/// Facet k is a flat piece of the boundary owned by particle particle[k]: its area (m^2;
/// in 2-D length times the thickness), unit outward normal and centroid (dim values each,
/// point-major). side[k] is 2 * axis + (1 at the max face) for a face of the box, -1 for any
/// other surface (a hole). Exact for a body whose particles tile it: sum_k A_k n_k (x) y_k =
/// (sum of the volumes) I, the discrete divergence theorem the formulation relies on.
struct BoundaryFacets {
  int dim = 0;
  std::vector<ParticleId> particle;
  std::vector<double> area;
  std::vector<double> normal;
  std::vector<double> centroid;
  std::vector<int> side;

  std::size_t size() const { return particle.size(); }
  bool empty() const { return particle.empty(); }
};

/// The facets of a lattice (make_lattice) filling the box minus holes: the faces of the
/// lattice cells that border the outside of the box or a cell dropped inside a hole. A hole
/// thus has a staircase surface (axis-aligned normals) whose facets tile it exactly. The
/// cell of a jittered particle is found from its position (jitter < 1 keeps it in its cell).
BoundaryFacets lattice_facets(const BoxGeometry& box, const PointCloud& cloud);

/// sum_k A_k n_k (x) y_k - (sum_i V_i) I, largest entry over the total volume: zero (to
/// rounding) when the facets close the body the volumes fill.
double divergence_theorem_defect(const BoundaryFacets& facets, const PointCloud& cloud);

}  // namespace perinom
