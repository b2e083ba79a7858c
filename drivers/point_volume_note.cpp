#include "point_volume_note.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "perinom/neighbors/search.hpp"

namespace perinom::cli {

double point_volume_ratio(const Problem& p) {
  const PointCloud& c = p.cloud;
  if (c.size() < 2) return 1.0;
  const Families nearest = knn_families(c, 1);
  const double t = c.dim == 2 ? p.scene.geometry.thickness : 1.0;
  std::vector<double> ratio(c.size());
  for (std::size_t i = 0; i < c.size(); ++i) ratio[i] = std::pow(c.volume[i] / t, 1.0 / c.dim) / nearest.support[i];
  std::nth_element(ratio.begin(), ratio.begin() + ratio.size() / 2, ratio.end());
  return ratio[ratio.size() / 2];
}

std::string point_volume_warning(const Problem& p) {
  const Scene& s = p.scene;
  if (s.body_files.points.empty()) return "";
  const double r = point_volume_ratio(p);
  if (r >= 1.0 / kPointVolumeFactor && r <= kPointVolumeFactor) return "";
  char buf[900];
  if (s.dim == 2)
    std::snprintf(buf, sizeof buf,
                  "geometry.points: %s: the volumes do not fit the positions: the median particle's (volume / "
                  "geometry.thickness)^(1/2) is %.3g times its distance to its nearest particle (1 on a lattice): 2-D "
                  "volumes are areas times geometry.thickness (%g m%s), in m^3 with the positions in m; the mean spacing "
                  "taken from them (%g m) sets the line probes' band and the thin-body note",
                  s.body_files.points.c_str(), r, s.geometry.thickness,
                  s.geometry.thickness == 1.0 ? ", the default" : "", p.mean_size);
  else
    std::snprintf(buf, sizeof buf,
                  "geometry.points: %s: the volumes do not fit the positions: the median particle's volume^(1/3) is "
                  "%.3g times its distance to its nearest particle (1 on a lattice): volumes in m^3 with the positions "
                  "in m (mm^3 would be 1000 times); the mean spacing taken from them (%g m) sets the line probes' band "
                  "and the thin-body note, and without facets the volumes weigh every force",
                  s.body_files.points.c_str(), r, p.mean_size);
  return buf;
}

}  // namespace perinom::cli
