#pragma once
// What `perinom run` writes of a state: VTK point data, probe values.
#include <string>
#include <vector>

#include "perinom/io/json_writer.hpp"
#include "perinom/io/vtk_writer.hpp"
#include "perinom/scene/problem.hpp"

namespace perinom::cli {

/// Adds one snapshot at `time` to the series and rewrites the .pvd: displacement, stress,
/// von Mises, mean stress, volume; where the body has boundary facets (the consistent
/// formulation) the surface stress and its von Mises stress, reconstructed at the facets
/// (NaN off the surface); the improved formulation's subregions; with plasticity the
/// committed equivalent plastic strain, plastic strain tensor and yield flag (1: the particle
/// has yielded, xi > 0). A thin plate writes its own fields (plate_output.hpp). With output.csv the same point data also go to
/// dir/NAME_<index>.csv (the .vtu's name with .csv), one row per particle, for scripts.
/// @throws SolveError naming the field and particle, before writing anything, if a field
/// holds NaN or Inf (the solvers treat it as a failed NaN/Inf guard).
void add_snapshot(io::PvdSeries& series, double time, const Problem& p, const std::vector<double>& u,
                  const std::string& dir = "");

/// The probes' fields at u (stress, grad u, the committed plastic states, and grad sigma when a
/// point probe reconstructs a stress field).
struct ProbeState {
  std::vector<double> sigma, H, grad_sigma;
  ProbeState(const Problem& p, const std::vector<double>& u);
  ProbeFields fields(const Problem& p, const std::vector<double>& u) const {
    return {p.cloud, u, sigma, H, p.model->plastic(), grad_sigma.empty() ? nullptr : &grad_sigma};
  }
};

}  // namespace perinom::cli
