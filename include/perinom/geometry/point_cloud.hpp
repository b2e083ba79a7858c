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

/// The listed particles of `cloud` as a cloud of their own, in that order (a rank's local
/// part, a plate's part with its mirrors).
PointCloud subcloud(const PointCloud& cloud, const std::vector<ParticleId>& particles);

}  // namespace perinom
