#include "perinom/fracture/bond_measures.hpp"


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
  per_live_bond(graph, s, HourglassStrain{cloud.dim, cloud.x.data(), u, H});
}

void bond_stretches(const PointCloud& cloud, const BondGraph& graph, const double* u, std::vector<double>& s) {
  per_live_bond(graph, s, BondStretch{cloud.dim, cloud.x.data(), u});
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

std::vector<double> first_break_event(const BondGraph& graph) {
  std::vector<double> e(graph.rows(), 0.0);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t i = 0; i < graph.rows(); ++i) {
    std::uint32_t first = 0;
    for (Offset k = graph.begin(i); k < graph.end(i); ++k) {
      const std::uint32_t e = graph.event(k);  // 0: alive, or cut at build time
      if (e > 0 && (first == 0 || e < first)) first = e;
    }
    e[i] = first;
  }
  return e;
}

}  // namespace perinom
