#include "perinom/neighbors/local_part.hpp"

#include <algorithm>
#include <nanoflann.hpp>
#include <stdexcept>
#include <utility>

namespace perinom {
namespace {

/// The owned particles for nanoflann: a k-d tree over them answers "how far is the nearest
/// owned particle" for each candidate ghost.
struct OwnedAdaptor {
  const PointCloud& cloud;
  const ParticleId* owned;
  std::size_t count;
  std::size_t kdtree_get_point_count() const { return count; }
  double kdtree_get_pt(std::size_t k, std::size_t a) const { return cloud.x[owned[k] * cloud.dim + a]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const { return false; }
};

}  // namespace

LocalPart local_part(const PointCloud& cloud, const std::vector<ParticleId>& order, int ranks, int rank,
                     double horizon) {
  const std::size_t n = cloud.size();
  const int d = cloud.dim;
  if (ranks < 1 || rank < 0 || rank >= ranks || order.size() != n || !(horizon >= 0.0))
    throw std::invalid_argument("local_part: a rank outside 0..ranks-1, an order of another size or a negative horizon");
  const double reach = 2.0 * horizon * (1.0 + 1e-9), near2 = horizon * horizon * (1.0 + 2e-9);
  LocalPart part;
  part.first = n * rank / ranks;
  const std::size_t last = n * (rank + 1) / ranks;
  part.owned = last - part.first;
  part.particles.assign(order.begin() + static_cast<std::ptrdiff_t>(part.first),
                        order.begin() + static_cast<std::ptrdiff_t>(last));
  for (std::size_t k = part.first; k < last; ++k) part.global.push_back(static_cast<std::int64_t>(k));
  if (part.owned == 0) return part;

  // Candidates: the other particles inside the owned bounding box grown by the reach; each
  // is a ghost when its nearest owned particle lies within the reach.
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  for (int a = 0; a < d; ++a) {
    lo[a] = hi[a] = cloud.x[part.particles[0] * d + a];
    for (const ParticleId i : part.particles)
      lo[a] = std::min(lo[a], cloud.x[i * d + a]), hi[a] = std::max(hi[a], cloud.x[i * d + a]);
  }
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, OwnedAdaptor>,
                                                   OwnedAdaptor, -1, std::size_t>;
  OwnedAdaptor adaptor{cloud, part.particles.data(), part.owned};
  Tree tree(d, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  tree.buildIndex();
  const double r2 = reach * reach;
  std::vector<std::pair<std::int64_t, ParticleId>> near, far;
  for (std::size_t k = 0; k < n; ++k) {
    if (k >= part.first && k < last) continue;
    const ParticleId j = order[k];
    const double* p = cloud.point(j);
    bool inside = true;
    for (int a = 0; a < d; ++a) inside = inside && p[a] >= lo[a] - reach && p[a] <= hi[a] + reach;
    if (!inside) continue;
    std::size_t nearest = 0;
    double dist2 = 0.0;
    tree.knnSearch(p, 1, &nearest, &dist2);
    if (dist2 <= near2) near.emplace_back(static_cast<std::int64_t>(k), j);
    else if (dist2 <= r2) far.emplace_back(static_cast<std::int64_t>(k), j);
  }
  // k ascends: each group is already in curve order.
  part.near = near.size();
  for (const auto* group : {&near, &far})
    for (const auto& [k, j] : *group) part.global.push_back(k), part.particles.push_back(j);
  return part;
}

std::unordered_map<ParticleId, std::size_t> owned_index(const LocalPart& part) {
  std::unordered_map<ParticleId, std::size_t> at;
  at.reserve(part.owned);
  for (std::size_t p = 0; p < part.owned; ++p) at.emplace(part.particles[p], p);
  return at;
}

Families local_families(const Families& whole, const LocalPart& part) {
  std::vector<std::int64_t> local(whole.particles(), -1);
  for (std::size_t p = 0; p < part.particles.size(); ++p) local[part.particles[p]] = std::int64_t(p);
  Families f;
  f.offsets.reserve(part.particles.size() + 1);
  f.support.reserve(part.particles.size());
  for (const ParticleId i : part.particles) {
    for (Offset k = whole.begin(i); k < whole.end(i); ++k)
      if (const std::int64_t j = local[whole.neighbors[k]]; j >= 0) f.neighbors.push_back(ParticleId(j));
    f.offsets.push_back(Offset(f.neighbors.size()));
    f.support.push_back(whole.support[i]);
  }
  return f;
}

}  // namespace perinom
