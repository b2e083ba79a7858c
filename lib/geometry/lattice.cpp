#include "perinom/geometry/lattice.hpp"

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "perinom/core/error.hpp"

namespace perinom {

bool Hole::contains(const double* p, int dim) const {
  double r2 = 0.0;
  for (int a = 0; a < dim; ++a) {
    if (shape == Shape::cylinder && a == axis) continue;
    const double d = p[a] - center[a];
    r2 += d * d;
  }
  return r2 < radius * radius;
}

PointCloud make_lattice(const BoxGeometry& box, double dx, double jitter, std::uint64_t seed) {
  const int d = box.dim;
  char text[200];
  if (d != 2 && d != 3) throw InputError("BoxGeometry::dim = " + std::to_string(d) + ": must be 2 or 3");
  if (!(dx > 0.0 && std::isfinite(dx))) {
    std::snprintf(text, sizeof text, "make_lattice: dx = %g: must be positive and finite", dx);
    throw InputError(text);
  }
  for (int a = 0; a < d; ++a)
    if (!(box.min[a] < box.max[a])) {
      std::snprintf(text, sizeof text, "BoxGeometry: min[%d] = %g is not below max[%d] = %g (an empty or inverted box)",
                    a, box.min[a], a, box.max[a]);
      throw InputError(text);
    }
  std::array<long, 3> n{1, 1, 1};
  PointCloud cloud;
  cloud.dim = d;
  cloud.dx = dx;
  cloud.spacing.assign(d, dx);
  double cell_volume = (d == 2) ? box.thickness : 1.0;
  // Ids are 32-bit; refuse a mistyped dx before trying to allocate the lattice. The counts
  // are formed in double first: lround of 1e298 (dx = 1e-300) is undefined behaviour.
  double count = 1.0;
  for (int a = 0; a < d; ++a) count *= std::max(1.0, std::round((box.max[a] - box.min[a]) / dx));
  if (!(count <= 2.0e9))
    throw InputError("discretization.dx: the box holds about " + std::to_string(count).substr(0, 12) +
                     " lattice cells at this spacing, more than perinom's 2e9 particle limit");
  for (int a = 0; a < d; ++a) {
    const double length = box.max[a] - box.min[a];
    n[a] = std::max(1L, std::lround(length / dx));
    cloud.spacing[a] = length / n[a];
    cell_volume *= cloud.spacing[a];
  }
  std::vector<std::size_t> removed(box.holes.size(), 0);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> offset(-0.5, 0.5);
  const long nz = (d == 3) ? n[2] : 1;
  for (long k = 0; k < nz; ++k)
    for (long j = 0; j < n[1]; ++j)
      for (long i = 0; i < n[0]; ++i) {
        const long idx[3] = {i, j, k};
        double p[3];
        for (int a = 0; a < d; ++a) p[a] = box.min[a] + (idx[a] + 0.5) * cloud.spacing[a];
        bool inside_hole = false;
        for (std::size_t h = 0; h < box.holes.size(); ++h)
          if (box.holes[h].contains(p, d)) inside_hole = true, ++removed[h];
        if (inside_hole) continue;
        if (jitter > 0.0)
          for (int a = 0; a < d; ++a) p[a] += jitter * cloud.spacing[a] * offset(rng);
        cloud.x.insert(cloud.x.end(), p, p + d);
        cloud.volume.push_back(cell_volume);
      }
  if (cloud.size() == 0) throw InputError("the box minus its holes holds no particle");
  // A hole that holds no lattice point is not in the model: the user's body would run
  // without it (a centre in mm in a box in m, a hole finer than the spacing).
  for (std::size_t h = 0; h < box.holes.size(); ++h) {
    if (removed[h] > 0) continue;
    std::snprintf(text, sizeof text, "holes[%zu]: removes no particle: the hole lies outside the box or between "
                  "the particles (radius %g m, spacing %g m)", h, box.holes[h].radius, dx);
    throw InputError(text);
  }
  return cloud;
}

}  // namespace perinom
