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

/// The value of a probe's field at particle i (SI units), from the displacement u and the
/// 3 x 3 stresses sigma (N x 9).
double probe_value(const ProbeSpec& spec, int dim, std::size_t i, const std::vector<double>& u,
                   const std::vector<double>& sigma);

}  // namespace perinom
