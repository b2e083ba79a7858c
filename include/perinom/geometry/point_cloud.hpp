#pragma once
/// @file A cloud of particles: reference positions and volumes.
#include <cstddef>
#include <vector>

#include "perinom/core/types.hpp"

namespace perinom {

/// Particles in d = 2 or 3 dimensions.
/// Layout: x holds size() * dim coordinates, point-major (x[i*dim + a]), in metres;
/// volume[i] in m^3 (in 2-D: area times thickness).
struct PointCloud {
  int dim = 3;
  double dx = 0.0;               ///< nominal spacing (m)
  std::vector<double> spacing;   ///< lattice spacing per axis (m), dim entries
  std::vector<double> x;
  std::vector<double> volume;

  std::size_t size() const { return volume.size(); }
  const double* point(std::size_t i) const { return x.data() + i * dim; }
};

/// Throws InputError unless the cloud is well formed: dim 2 or 3, x holding size() * dim
/// coordinates, every coordinate finite and every volume positive and finite (naming the first
/// particle that is not). O(N); the
/// entry points that index x by size() and dim call it once (the neighbour searches, the models).
void check_cloud(const PointCloud& cloud);

/// The listed particles of `cloud` as a cloud of their own, in that order (a rank's local
/// part, a plate's part with its mirrors).
PointCloud subcloud(const PointCloud& cloud, const std::vector<ParticleId>& particles);

}  // namespace perinom
