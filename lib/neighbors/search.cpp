#include "perinom/neighbors/search.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <nanoflann.hpp>

#include "perinom/core/error.hpp"

namespace perinom {
namespace {

/// Concatenates per-particle neighbour lists into CSR.
Families to_csr(std::vector<std::vector<ParticleId>>& rows, std::vector<double> support) {
  Families f;
  f.offsets.resize(rows.size() + 1, 0);
  for (std::size_t i = 0; i < rows.size(); ++i)
    f.offsets[i + 1] = f.offsets[i] + static_cast<Offset>(rows[i].size());
  f.neighbors.reserve(f.offsets.back());
  for (auto& r : rows) {
    std::sort(r.begin(), r.end());
    f.neighbors.insert(f.neighbors.end(), r.begin(), r.end());
    std::vector<ParticleId>().swap(r);
  }
  f.support = std::move(support);
  return f;
}

struct CloudAdaptor {
  const PointCloud& cloud;
  std::size_t kdtree_get_point_count() const { return cloud.size(); }
  double kdtree_get_pt(std::size_t i, std::size_t a) const { return cloud.x[i * cloud.dim + a]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const { return false; }
};

}  // namespace

Families radius_families(const PointCloud& cloud, double delta) {
  const int d = cloud.dim;
  const std::size_t n = cloud.size();
  if (!(delta > 0.0)) throw InputError("neighbour search: the horizon must be positive");
  check_cloud(cloud);
  // No particles, no families (a rank that owns none); the bounding box below reads x[0].
  if (n == 0) return Families{};
  std::array<double, 3> lo{0, 0, 0}, hi{0, 0, 0};
  for (int a = 0; a < d; ++a) {
    lo[a] = hi[a] = cloud.x[a];
    for (std::size_t i = 0; i < n; ++i) {
      lo[a] = std::min(lo[a], cloud.x[i * d + a]);
      hi[a] = std::max(hi[a], cloud.x[i * d + a]);
    }
  }
  // Buckets of side `cell` >= delta, so the neighbours of a particle lie in the 3^d
  // buckets around it. A horizon tiny against the cloud (delta = 1e-300) would ask for more
  // buckets than a long counts: then they grow until there are about as many as particles.
  double cell = delta * (1.0 + kHorizonTie), buckets = 1.0;
  for (int a = 0; a < d; ++a) buckets *= (hi[a] - lo[a]) / cell + 1.0;
  const double most = 8.0 * static_cast<double>(n) + 64.0;
  if (!(buckets <= most)) cell = std::max(cell, std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]}) /
                                                     std::pow(most, 1.0 / d));
  std::array<long, 3> cells{1, 1, 1};
  for (int a = 0; a < d; ++a)
    cells[a] = std::max(1L, static_cast<long>(std::min((hi[a] - lo[a]) / cell, most)) + 1);
  auto cell_of = [&](const double* p, int a) {
    return std::min(cells[a] - 1, static_cast<long>((p[a] - lo[a]) / cell));
  };
  // Bucket the particles by cell (counting sort).
  const long ncell = cells[0] * cells[1] * cells[2];
  std::vector<Offset> start(ncell + 1, 0);
  std::vector<long> cell_id(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double* p = cloud.point(i);
    long c = 0;
    for (int a = d - 1; a >= 0; --a) c = c * cells[a] + cell_of(p, a);
    cell_id[i] = c;
    ++start[c + 1];
  }
  for (long c = 0; c < ncell; ++c) start[c + 1] += start[c];
  std::vector<ParticleId> sorted(n);
  {
    std::vector<Offset> next(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < n; ++i) sorted[next[cell_id[i]]++] = static_cast<ParticleId>(i);
  }
  std::vector<std::vector<ParticleId>> rows(n);
  // Ties within rounding belong to the family: on a lattice with a whole-number horizon ratio
  // (3.0) the neighbours at exactly delta were kept or dropped by the rounding of their
  // coordinates, so a symmetric plate answered asymmetrically (3.7% between mirrored
  // particles) and the answer changed with the unit of length (1.4% from m to mm).
  const double r2 = delta * delta * (1.0 + kHorizonTie);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t i = 0; i < n; ++i) {
    const double* p = cloud.point(i);
    long c0[3] = {0, 0, 0};
    for (int a = 0; a < d; ++a) c0[a] = cell_of(p, a);
    const long zr = (d == 3) ? 1 : 0;
    for (long dz = -zr; dz <= zr; ++dz)
      for (long dy = -1; dy <= 1; ++dy)
        for (long dxc = -1; dxc <= 1; ++dxc) {
          const long c[3] = {c0[0] + dxc, c0[1] + dy, c0[2] + dz};
          if (c[0] < 0 || c[1] < 0 || c[2] < 0 || c[0] >= cells[0] || c[1] >= cells[1] ||
              c[2] >= cells[2])
            continue;
          const long cid = (c[2] * cells[1] + c[1]) * cells[0] + c[0];
          for (Offset s = start[cid]; s < start[cid + 1]; ++s) {
            const ParticleId j = sorted[s];
            if (static_cast<std::size_t>(j) == i) continue;
            const double* q = cloud.point(j);
            double dist2 = 0.0;
            for (int a = 0; a < d; ++a) dist2 += (q[a] - p[a]) * (q[a] - p[a]);
            if (dist2 <= r2) rows[i].push_back(j);
          }
        }
  }
  return to_csr(rows, std::vector<double>(n, delta));
}

Families knn_families(const PointCloud& cloud, int k) {
  const std::size_t n = cloud.size();
  if (k < 1) throw InputError("neighbour search: k must be at least 1");
  check_cloud(cloud);
  if (static_cast<std::size_t>(k) >= n)
    throw InputError("neighbour search: k = " + std::to_string(k) + " neighbours but only " +
                     std::to_string(n) + " particles");
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<
      nanoflann::L2_Simple_Adaptor<double, CloudAdaptor>, CloudAdaptor, -1, std::size_t>;
  CloudAdaptor adaptor{cloud};
  Tree tree(cloud.dim, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  tree.buildIndex();
  std::vector<std::vector<ParticleId>> rows(n);
  std::vector<double> support(n, 0.0);
#pragma omp parallel
  {
    std::vector<std::size_t> idx(k + 1);
    std::vector<double> dist2(k + 1);
#pragma omp for schedule(dynamic, 256)
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t found = tree.knnSearch(cloud.point(i), k + 1, idx.data(), dist2.data());
      for (std::size_t m = 0; m < found; ++m) {
        if (idx[m] == i) continue;
        if (static_cast<int>(rows[i].size()) == k) break;
        rows[i].push_back(static_cast<ParticleId>(idx[m]));
        support[i] = std::max(support[i], std::sqrt(dist2[m]));
      }
    }
  }
  return to_csr(rows, std::move(support));
}

}  // namespace perinom
