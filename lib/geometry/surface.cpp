#include "perinom/geometry/surface.hpp"

#include <algorithm>
#include <cmath>

namespace perinom {

Surface find_surface(const BoxGeometry& box, const PointCloud& cloud, double band_width) {
  const int d = cloud.dim;
  const std::size_t n = cloud.size();
  Surface s;
  s.normal_over_h.assign(n * d, 0.0);
  s.on_surface.assign(n, 0);
  s.in_band.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const double* p = cloud.point(i);
    double* m = s.normal_over_h.data() + i * d;
    double distance = INFINITY;  // to the nearest surface
    for (int a = 0; a < d; ++a) {
      const double h = cloud.spacing[a];
      const double lo = p[a] - box.min[a], hi = box.max[a] - p[a];
      if (lo < h) m[a] -= 1.0 / h, s.on_surface[i] = 1;
      if (hi < h) m[a] += 1.0 / h, s.on_surface[i] = 1;
      distance = std::min({distance, lo, hi});
    }
    for (const auto& hole : box.holes) {
      double r2 = 0.0, radial[3] = {0, 0, 0};
      for (int a = 0; a < d; ++a) {
        if (hole.shape == Hole::Shape::cylinder && a == hole.axis) continue;
        radial[a] = p[a] - hole.center[a];
        r2 += radial[a] * radial[a];
      }
      const double r = std::sqrt(r2), gap = r - hole.radius;
      distance = std::min(distance, gap);
      if (gap < cloud.dx && r > 0.0) {
        // The outward normal of the body points into the hole.
        for (int a = 0; a < d; ++a) m[a] -= radial[a] / r / cloud.dx;
        s.on_surface[i] = 1;
      }
    }
    s.in_band[i] = distance < band_width ? 1 : 0;
    (s.in_band[i] ? s.band : s.interior).push_back(static_cast<ParticleId>(i));
  }
  return s;
}

}  // namespace perinom
