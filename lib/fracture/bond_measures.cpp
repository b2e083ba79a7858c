#include "perinom/fracture/bond_measures.hpp"

#include <cmath>

namespace perinom {
namespace {

// s[k] = value(i, j) for every live bond k = (i, j), 0 for a dead one; rows in parallel.
template <class Value>
void per_live_bond(const BondGraph& g, std::vector<double>& s, Value&& value) {
  s.assign(g.bonds(), 0.0);
  const std::size_t n = g.rows();
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t i = 0; i < n; ++i)
    for (Offset k = g.begin(i); k < g.end(i); ++k)
      if (g.alive(k)) s[k] = value(i, static_cast<std::size_t>(g.col(k)));
}

}  // namespace

void hourglass_strains(const PointCloud& cloud, const BondGraph& graph, const double* u, const double* H,
                       std::vector<double>& s) {
  const int d = cloud.dim;
  const double* x = cloud.x.data();
  per_live_bond(graph, s, [&](std::size_t i, std::size_t j) {
    double xi[3], z2 = 0.0, l2 = 0.0;
    for (int b = 0; b < d; ++b) xi[b] = x[j * d + b] - x[i * d + b], l2 += xi[b] * xi[b];
    for (int a = 0; a < d; ++a) {
      double z = u[j * d + a] - u[i * d + a];
      for (int b = 0; b < d; ++b) z -= H[(i * d + a) * d + b] * xi[b];
      z2 += z * z;
    }
    return std::sqrt(z2 / l2);
  });
}

void bond_stretches(const PointCloud& cloud, const BondGraph& graph, const double* u, std::vector<double>& s) {
  const int d = cloud.dim;
  const double* x = cloud.x.data();
  per_live_bond(graph, s, [&](std::size_t i, std::size_t j) {
    double l2 = 0.0, y2 = 0.0;
    for (int a = 0; a < d; ++a) {
      const double xi = x[j * d + a] - x[i * d + a];
      const double y = xi + u[j * d + a] - u[i * d + a];
      l2 += xi * xi, y2 += y * y;
    }
    const double l = std::sqrt(l2);
    return (std::sqrt(y2) - l) / l;
  });
}

void bond_stresses(const BondGraph& graph, const std::vector<double>& sigma1, std::vector<double>& t) {
  per_live_bond(graph, t, [&](std::size_t i, std::size_t j) { return 0.5 * (sigma1[i] + sigma1[j]); });
}

std::vector<double> damage(const BondGraph& graph, const std::vector<double>& volume) {
  std::vector<double> d(graph.rows(), 0.0);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t i = 0; i < graph.rows(); ++i) {
    double dead = 0.0, all = 0.0;
    for (Offset k = graph.begin(i); k < graph.end(i); ++k) {
      const double v = volume[graph.col(k)];
      all += v;
      if (!graph.alive(k)) dead += v;
    }
    d[i] = all > 0.0 ? dead / all : 0.0;
  }
  return d;
}

}  // namespace perinom
