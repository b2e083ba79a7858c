#pragma once
/// @file A scene turned into what the solvers consume: particles, families, the assembled
/// model, the loading and the resolved probes.
#include <memory>
#include <vector>

#include "perinom/core/timer.hpp"
#include "perinom/models/correspondence.hpp"
#include "perinom/models/loading.hpp"
#include "perinom/scene/scene.hpp"

namespace perinom {

/// A probe bound to particles: the nearest particle of a point, or the particles within half
/// a spacing of a line segment ordered along it (s = distance from `from`, m).
struct BoundProbe {
  ProbeSpec spec;
  std::vector<ParticleId> particles;
  std::vector<double> along;
};

struct Problem {
  Scene scene;
  PointCloud cloud;
  std::size_t bonds = 0;
  std::unique_ptr<CorrespondenceModel> model;
  Loading loading;
  std::vector<BoundProbe> probes;
};

/// Builds the problem (lattice, families, operators, loading, probes). Phases are timed
/// in `timer` when given. Throws InputError for a region that selects no particle or a
/// singular shape tensor.
Problem build_problem(const Scene& scene, PhaseTimer* timer = nullptr);

/// The fields probes read: displacement u (N x d), 3 x 3 stresses sigma (N x 9), and the
/// displacement gradient H (N x d x d) for reconstructed point probes.
struct ProbeFields {
  const PointCloud& cloud;
  const std::vector<double>& u;
  const std::vector<double>& sigma;
  const std::vector<double>& H;
};

/// The value of a probe's field at particle i (SI units).
double probe_value(const ProbeSpec& spec, std::size_t i, const ProbeFields& f);

/// A point probe's value: at its nearest particle, or, with `reconstruct`, at the probe's
/// point through that particle's first-order reconstruction u_i + (grad u)_i (x - x_i).
double point_probe_value(const BoundProbe& probe, const ProbeFields& f);

}  // namespace perinom
