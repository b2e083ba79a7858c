#include "perinom/geometry/surface_bend.hpp"

#include <algorithm>
#include <cmath>

#include "perinom/neighbors/search.hpp"

namespace perinom {

SurfaceBend tightest_concave_bend(const BoundaryFacets& facets, const PointCloud& cloud, double thickness_2d,
                                  double length_scale, double reach) {
  SurfaceBend bend;
  const int d = facets.dim;
  const std::size_t n = facets.size();
  const int k_nearest = 2 * d;
  if (n <= static_cast<std::size_t>(k_nearest)) return bend;
  PointCloud centroids;
  centroids.dim = d;
  centroids.x = facets.centroid;
  centroids.volume.assign(n, 1.0);
  const Families near = knn_families(centroids, k_nearest);
  const double t = d == 2 ? thickness_2d : 1.0;
  const double pi = std::acos(-1.0), lowest = 0.1 * pi / 180.0, sharpest = 75.0 * pi / 180.0;
  const auto spacing = [&](std::size_t k) {
    return std::max(std::pow(cloud.volume[facets.particle[k]] / t, 1.0 / d), length_scale);
  };
  for (std::size_t k = 0; k < n; ++k) {
    const double* nk = &facets.normal[k * d];
    const double* ck = &facets.centroid[k * d];
    for (Offset q = near.begin(k); q < near.end(k); ++q) {
      const std::size_t m = near.neighbors[q];
      const double* nm = &facets.normal[m * d];
      const double* cm = &facets.centroid[m * d];
      double cos_turn = 0.0, toward = 0.0, r2 = 0.0;
      for (int a = 0; a < d; ++a) {
        cos_turn += nk[a] * nm[a];
        toward += nk[a] * (cm[a] - ck[a]);
        r2 += (cm[a] - ck[a]) * (cm[a] - ck[a]);
      }
      const double theta = std::acos(std::clamp(cos_turn, -1.0, 1.0));
      if (theta < lowest || theta > sharpest || toward <= 0.0) continue;
      const double radius = std::sqrt(r2) / (2.0 * std::sin(0.5 * theta));
      const double ratio = radius / (0.5 * (spacing(k) + spacing(m)));
      if (ratio < reach && ratio < bend.spacings) bend.radius = radius, bend.spacings = ratio, bend.facet = k;
    }
  }
  return bend;
}

}  // namespace perinom
