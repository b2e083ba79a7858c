#include "perinom/geometry/point_cloud.hpp"

namespace perinom {

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
