#pragma once
// perinom run for load-path scenes (plasticity, stages, solver.type lbc).
#include <set>
#include <string>
#include <vector>

#include "perinom/core/progress.hpp"
#include "perinom/core/timer.hpp"
#include "perinom/io/json_writer.hpp"
#include "perinom/io/vtk_writer.hpp"
#include "perinom/scene/problem.hpp"
#include "perinom/scene/registry.hpp"
#include "perinom/solvers/load_path.hpp"
#include "difference.hpp"

namespace perinom::cli {

/// Point-probe values after every load step, for the histories and the Newton check.
struct ProbeHistory {
  static constexpr int probe_columns = 5;  ///< per point probe
  std::vector<std::vector<double>> rows;  ///< stage, step, load_factor, then per probe: value,
                                          ///< von_mises, mean_stress, equivalent_strain, eq_plastic_strain
  /// The stress measure's largest norms along the path, kept when the damaged Newton check will
  /// compare a broken body's end (a bar broken through ends with rounding for stress).
  PathScale stress;
  void record(const Problem& p, const LoadStepRecord& r, const std::vector<double>& u);
  /// A row's first columns: stage, step, load_factor.
  static std::vector<double> step_columns(const LoadStepRecord& r);
  /// probe_NAME_history.csv for each point probe.
  void write(const Problem& p, const std::string& dir) const;
};

/// Lines within a long load step (a cascade of breaks, a hard balance) every 10 s, so a run
/// that spends minutes in one step is seen to be alive; quiet while the steps' own lines
/// come often enough. A solver's phase line (Newton's predicted factors, once per stage) is
/// printed the first time its text comes: the balances of every step repeat theirs.
class StepProgress : public Progress {
 public:
  void update(const ProgressSample& s) override;
  void phase(const char* what) override;
  /// A step's own line was printed: the next step starts.
  void step_done() { last_line_ = step_start_ = wall_seconds(); }

 private:
  double last_line_ = wall_seconds(), step_start_ = last_line_;
  std::set<std::string> phases_;  // printed already
  std::int64_t newton_base_ = -1;  // Newton's iteration count before the step being solved; -1: none yet
};

/// A point probe's columns of a ProbeHistory row (value, von_mises, mean_stress,
/// equivalent_strain, eq_plastic_strain) into out[0..5).
void add_probe_values(const ProbeReadout& readout, const BoundProbe& probe, double* out);

/// The load path's first lines (stages, steps, scheme) and the step table's header.
void print_load_path_plan(const Scene& scene, const std::vector<LoadStage>& stages, const LoadPathOptions& opt);
/// One load step's line of the table.
void print_load_step(const Scene& scene, const LoadStepRecord& r);
/// Whether a snapshot is due after `done` load steps (output.vtk_steps, output.vtk_every).
bool snapshot_due(const Scene& scene, std::int64_t done);

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
