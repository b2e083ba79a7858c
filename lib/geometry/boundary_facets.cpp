#include "perinom/geometry/boundary_facets.hpp"

#include <algorithm>
#include <cmath>

namespace perinom {

BoundaryFacets lattice_facets(const BoxGeometry& box, const PointCloud& cloud) {
  const int d = cloud.dim;
  BoundaryFacets f;
  f.dim = d;
  std::array<long, 3> cells{1, 1, 1};
  for (int a = 0; a < d; ++a) cells[a] = std::lround((box.max[a] - box.min[a]) / cloud.spacing[a]);
  const auto in_hole = [&](const double* p) {
    return std::any_of(box.holes.begin(), box.holes.end(), [&](const Hole& h) { return h.contains(p, d); });
  };
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    double centre[3] = {0, 0, 0};
    long index[3] = {0, 0, 0};
    for (int a = 0; a < d; ++a) {
      const double h = cloud.spacing[a];
      index[a] = std::clamp(static_cast<long>(std::floor((cloud.x[i * d + a] - box.min[a]) / h)), 0L, cells[a] - 1);
      centre[a] = box.min[a] + (index[a] + 0.5) * h;
    }
    for (int a = 0; a < d; ++a)
      for (int s = -1; s <= 1; s += 2) {
        const double h = cloud.spacing[a];
        const long next = index[a] + s;
        int side = -2;  // -2: an inner face, no facet
        if (next < 0 || next >= cells[a]) {
          side = 2 * a + (s > 0 ? 1 : 0);
        } else {
          double p[3] = {centre[0], centre[1], centre[2]};
          p[a] += s * h;
          if (in_hole(p)) side = -1;
        }
        if (side == -2) continue;
        f.particle.push_back(static_cast<ParticleId>(i));
        f.area.push_back(cloud.volume[i] / h);
        f.side.push_back(side);
        for (int b = 0; b < d; ++b) {
          f.normal.push_back(b == a ? s : 0.0);
          f.centroid.push_back(centre[b] + (b == a ? 0.5 * s * h : 0.0));
        }
      }
  }
  return f;
}

double divergence_theorem_defect(const BoundaryFacets& f, const PointCloud& cloud) {
  const int d = cloud.dim;
  double volume = 0.0;
  for (const double v : cloud.volume) volume += v;
  double worst = 0.0;
  for (int a = 0; a < d; ++a)
    for (int b = 0; b < d; ++b) {
      double s = a == b ? -volume : 0.0;
      for (std::size_t k = 0; k < f.size(); ++k) s += f.area[k] * f.normal[k * d + a] * f.centroid[k * d + b];
      worst = std::max(worst, std::abs(s));
    }
  return worst / volume;
}

}  // namespace perinom
