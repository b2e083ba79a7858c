#pragma once
// For the refresh tests: random broken bonds, the families without them, an elastic material,
// and the relative differences of fields and of sparse rows.
#include <algorithm>
#include <cmath>
#include <map>
#include <cstdint>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include <catch2/catch.hpp>

#include "perinom/materials/linear_elastic.hpp"
#include "perinom/neighbors/families.hpp"
#include "clouds.hpp"

namespace perinom::test {

using Bond = std::pair<ParticleId, ParticleId>;

/// The families without the broken bonds (both directions), supports unchanged.
inline Families without(const Families& f, const std::set<Bond>& broken) {
  Families g;
  g.support = f.support;
  for (std::size_t i = 0; i < f.particles(); ++i) {
    for (Offset k = f.begin(i); k < f.end(i); ++k) {
      const ParticleId j = f.neighbors[k];
      if (!broken.count({static_cast<ParticleId>(i), j}) && !broken.count({j, static_cast<ParticleId>(i)}))
        g.neighbors.push_back(j);
    }
    g.offsets.push_back(static_cast<Offset>(g.neighbors.size()));
  }
  return g;
}

/// `count` distinct bonds of the families, drawn with a fixed seed.
inline std::vector<Bond> random_bonds(const Families& f, std::size_t count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::set<Bond> chosen;
  std::vector<Bond> out;
  while (out.size() < count) {
    const std::size_t i = rng() % f.particles();
    if (f.end(i) == f.begin(i)) continue;
    const ParticleId j = f.neighbors[f.begin(i) + static_cast<Offset>(rng() % (f.end(i) - f.begin(i)))];
    const Bond b{std::min<ParticleId>(i, j), std::max<ParticleId>(i, j)};
    if (chosen.insert(b).second) out.push_back({static_cast<ParticleId>(i), j});
  }
  return out;
}

/// E = 30 MPa, nu = 0.25, plane strain in 2-D.
inline LinearElastic elastic_material(int dim) {
  LinearElastic m;
  m.E = 30e6;
  m.nu = 0.25;
  m.density = 2000;
  m.dim = dim;
  m.plane = dim == 2 ? PlaneCondition::strain : PlaneCondition::none;
  return m;
}

/// max |a - b| / max |b|; requires equal sizes and a finite a.
inline double relative_difference(const std::vector<double>& a, const std::vector<double>& b) {
  REQUIRE(a.size() == b.size());
  double diff = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    REQUIRE(std::isfinite(a[k]));
    diff = std::max(diff, std::abs(a[k] - b[k]));
  }
  return diff / std::max(max_abs(b), 1e-300);
}

/// Sparse rows as (row, column) -> block values.
using Rows = std::map<std::pair<std::size_t, ParticleId>, std::vector<double>>;

/// The largest difference of two sets of rows (an entry one lacks counts as zero) over the
/// largest entry.
inline double rows_difference(const Rows& a, const Rows& b) {
  double diff = 0.0, scale = 0.0;
  auto sweep = [&](const Rows& x, const Rows& y) {
    for (const auto& [key, v] : x) {
      const auto it = y.find(key);
      for (std::size_t c = 0; c < v.size(); ++c) {
        const double w = it == y.end() ? 0.0 : it->second[c];
        diff = std::max(diff, std::abs(v[c] - w));
        scale = std::max(scale, std::abs(v[c]));
      }
    }
  };
  sweep(a, b);
  sweep(b, a);
  return diff / std::max(scale, 1e-300);
}

}  // namespace perinom::test
