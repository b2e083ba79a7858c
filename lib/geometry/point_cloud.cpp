#include "perinom/geometry/point_cloud.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "perinom/core/error.hpp"

namespace perinom {
namespace {

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

}  // namespace

void check_cloud(const PointCloud& cloud) {
  const int d = cloud.dim;
  if (d != 2 && d != 3) throw InputError("PointCloud::dim = " + std::to_string(d) + ": must be 2 or 3");
  if (cloud.x.size() != cloud.size() * d)
    throw InputError("PointCloud::x holds " + std::to_string(cloud.x.size()) + " coordinates for " +
                     std::to_string(cloud.size()) + " particles (PointCloud::volume) in " + std::to_string(d) +
                     "-D: needs " + std::to_string(cloud.size() * d));
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const double* p = cloud.point(i);
    bool finite = true;
    for (int a = 0; a < d; ++a) finite = finite && std::isfinite(p[a]);
    if (finite) continue;
    std::string at;
    for (int a = 0; a < d; ++a) at += (a ? ", " : "") + number(p[a]);
    throw InputError("PointCloud::x: particle " + std::to_string(i) + " at (" + at + ") has a coordinate that is not finite");
  }
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (!(cloud.volume[i] > 0.0 && std::isfinite(cloud.volume[i])))
      throw InputError("PointCloud::volume: particle " + std::to_string(i) + " has volume " +
                       number(cloud.volume[i]) + ": must be positive and finite");
}

PointCloud subcloud(const PointCloud& cloud, const std::vector<ParticleId>& particles) {
  PointCloud out;
  out.dim = cloud.dim;
  out.dx = cloud.dx;
  out.spacing = cloud.spacing;
  const int d = cloud.dim;
  out.x.reserve(particles.size() * d);
  out.volume.reserve(particles.size());
  for (const ParticleId i : particles) {
    out.x.insert(out.x.end(), cloud.x.begin() + i * d, cloud.x.begin() + (i + 1) * d);
    out.volume.push_back(cloud.volume[i]);
  }
  return out;
}

}  // namespace perinom
