#include "perinom/geometry/wall_thickness.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace perinom {
namespace {

/// The facets' centroids on a grid: (cell key, facet) sorted by key.
class FacetGrid {
 public:
  FacetGrid(const BoundaryFacets& f, double cell) : dim_(f.dim), cell_(cell) {
    for (int a = 0; a < dim_; ++a) origin_[a] = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < f.size(); ++k)
      for (int a = 0; a < dim_; ++a) origin_[a] = std::min(origin_[a], f.centroid[k * dim_ + a]);
    entries_.reserve(f.size());
    for (std::size_t k = 0; k < f.size(); ++k) entries_.emplace_back(key(index_of(&f.centroid[k * dim_])), k);
    std::sort(entries_.begin(), entries_.end());
  }

  std::array<std::int64_t, 3> index_of(const double* p) const {
    std::array<std::int64_t, 3> c{0, 0, 0};
    for (int a = 0; a < dim_; ++a) c[a] = static_cast<std::int64_t>(std::floor((p[a] - origin_[a]) / cell_));
    return c;
  }

  /// Calls visit(k) for every facet in cell c.
  template <class Visit>
  void each_in(const std::array<std::int64_t, 3>& c, Visit&& visit) const {
    const std::int64_t k = key(c);
    auto it = std::lower_bound(entries_.begin(), entries_.end(), std::make_pair(k, std::size_t(0)));
    for (; it != entries_.end() && it->first == k; ++it) visit(it->second);
  }

 private:
  static std::int64_t key(const std::array<std::int64_t, 3>& c) {
    // 21 bits per axis around an offset: 2 million cells a side, far beyond any cloud here.
    constexpr std::int64_t off = std::int64_t(1) << 20, mask = (std::int64_t(1) << 21) - 1;
    return ((c[0] + off) & mask) | (((c[1] + off) & mask) << 21) | (((c[2] + off) & mask) << 42);
  }

  int dim_;
  double cell_;
  std::array<double, 3> origin_{0, 0, 0};
  std::vector<std::pair<std::int64_t, std::size_t>> entries_;
};

}  // namespace

ThinSpot thinnest_wall(const BoundaryFacets& f, const PointCloud& cloud, double thickness_2d, double reach) {
  ThinSpot best;
  const int d = f.dim;
  if (f.empty() || d != cloud.dim) return best;
  const double t = d == 2 ? thickness_2d : 1.0;
  std::vector<double> h(f.size());
  double cell = 0.0;
  for (std::size_t k = 0; k < f.size(); ++k) {
    h[k] = std::pow(cloud.volume[f.particle[k]] / t, 1.0 / d);
    cell = std::max(cell, h[k]);
  }
  if (!(cell > 0.0)) return best;
  const FacetGrid grid(f, cell);
  for (std::size_t k = 0; k < f.size(); ++k) {
    const double* ck = &f.centroid[k * d];
    const double* nk = &f.normal[k * d];
    double nearest = std::numeric_limits<double>::infinity(), across = nearest;
    std::size_t opposite = k;
    auto consider = [&](std::size_t m) {
      const double* nm = &f.normal[m * d];
      double facing = 0.0, along = 0.0, r2 = 0.0;
      for (int a = 0; a < d; ++a) {
        const double r = f.centroid[m * d + a] - ck[a];
        facing += nk[a] * nm[a], along -= r * nk[a], r2 += r * r;
      }
      const double spacing = 0.5 * (h[k] + h[m]);
      if (facing >= -0.5 || along <= 0.0 || r2 - along * along >= spacing * spacing || along >= nearest) return;
      nearest = along, across = along / spacing, opposite = m;
    };
    // Step inward along -n_k by half a cell, visiting the cells around each new cell (a facet
    // seen twice is considered twice, harmlessly).
    std::array<std::int64_t, 3> last{};
    bool first = true;
    const double limit = reach * h[k] + cell;
    for (double s = 0.0; s <= limit && s <= nearest + cell; s += 0.5 * cell) {
      double p[3] = {0, 0, 0};
      for (int a = 0; a < d; ++a) p[a] = ck[a] - s * nk[a];
      const auto c = grid.index_of(p);
      if (!first && c == last) continue;
      first = false, last = c;
      for (int i = -1; i <= 1; ++i)
        for (int j = -1; j <= 1; ++j)
          for (int l = (d == 3 ? -1 : 0); l <= (d == 3 ? 1 : 0); ++l) grid.each_in({c[0] + i, c[1] + j, c[2] + l}, consider);
    }
    if (across < reach && across < best.across) best = {across, nearest, k, opposite};
  }
  return best;
}

}  // namespace perinom
