#pragma once
// Test support: small clouds, brute-force families, random fields.
#include <cmath>
#include <random>
#include <vector>

#include "perinom/geometry/lattice.hpp"
#include "perinom/neighbors/families.hpp"

namespace perinom::test {

/// An n^dim lattice on [0, n]^dim (spacing 1), jittered by `jitter` of the spacing.
inline PointCloud lattice(int dim, int n, double jitter, std::uint64_t seed = 7) {
  BoxGeometry box;
  box.dim = dim;
  for (int a = 0; a < dim; ++a) box.max[a] = n;
  return make_lattice(box, 1.0, jitter, seed);
}

/// All j != i with |x_j - x_i| <= delta, by checking every pair.
inline Families brute_force_radius(const PointCloud& c, double delta) {
  Families f;
  for (std::size_t i = 0; i < c.size(); ++i) {
    for (std::size_t j = 0; j < c.size(); ++j) {
      if (i == j) continue;
      double r2 = 0.0;
      for (int a = 0; a < c.dim; ++a) r2 += std::pow(c.x[j * c.dim + a] - c.x[i * c.dim + a], 2);
      if (r2 <= delta * delta) f.neighbors.push_back(static_cast<ParticleId>(j));
    }
    f.offsets.push_back(static_cast<Offset>(f.neighbors.size()));
    f.support.push_back(delta);
  }
  return f;
}

inline std::vector<double> random_field(std::size_t n, double scale, std::uint64_t seed = 3) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> v(n);
  for (auto& x : v) x = scale * u(rng);
  return v;
}

inline double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

}  // namespace perinom::test
