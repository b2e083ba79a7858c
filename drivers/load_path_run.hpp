#pragma once
// perinom run for load-path scenes (plasticity, stages, solver.type lbc).
#include <string>
#include <vector>

#include "perinom/io/json_writer.hpp"
#include "perinom/io/vtk_writer.hpp"
#include "perinom/scene/problem.hpp"
#include "perinom/scene/registry.hpp"
#include "perinom/solvers/load_path.hpp"

namespace perinom::cli {

/// Point-probe values after every load step, for the histories and the Newton check.
struct ProbeHistory {
  std::vector<std::vector<double>> rows;  ///< stage, step, load_factor, then per probe: value,
                                          ///< von_mises, mean_stress, equivalent_strain, eq_plastic_strain
  void record(const Problem& p, const LoadStepRecord& r, const std::vector<double>& u);
  /// probe_NAME_history.csv for each point probe.
  void write(const Problem& p, const std::string& dir) const;
};

/// Solves the load path into u with a per-step line on stdout, VTK snapshots after the
/// steps output.vtk_steps names (or every output.vtk_every steps; last_snapshot is the last
/// step written), and the probe histories. report.history has a row per load step; it and
/// the probe histories are written to dir after the first step and then every few seconds,
/// so a killed run leaves them (the caller writes them whole at the end).
/// Checkpoints and a resumed state as solve_load_path takes them.
SolveReport run_load_path(Problem& p, const std::string& dir, std::vector<double>& u, io::PvdSeries& series,
                          ProbeHistory& probes, std::int64_t& last_snapshot,
                          const Checkpoints<LoadPathState>& checkpoints = {}, const LoadPathState* resume = nullptr);

/// solver.check: newton on a load path: solves the same steps again with Newton from the
/// virgin state, compares the final fields and every step's probe values, then restores the
/// first solve's history (a model with history, Model::history()).
io::Json load_path_newton_check(Problem& p, const std::vector<double>& u, const ProbeHistory& first);

}  // namespace perinom::cli
