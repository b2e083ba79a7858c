#include "solve_scene.hpp"

#include <filesystem>
#include <optional>
#include <stdexcept>

#include "perinom/core/error.hpp"
#include "run_checkpoint.hpp"
#include "run_output.hpp"
#include "snapshot.hpp"
#include "terminal_progress.hpp"

namespace perinom::cli {
namespace {

SolveReport solve(Problem& p, const std::string& dir, std::vector<double>& u, io::PvdSeries& series,
                  ProbeHistory& probes, std::int64_t& last_snapshot, const Restart* restart) {
  const Scene& scene = p.scene;
  const std::size_t dofs = p.physics().dofs();
  // What a checkpoint holds beside the solver's state, as it is when the checkpoint is due.
  const auto progress_now = [&] {
    RunProgress run{series.steps(), last_snapshot, probes.rows, {}, {probes.stress.l2, probes.stress.max}};
    for (const auto& s : run.snapshots)  // (a stat a snapshot, at a checkpoint only)
      run.snapshot_csv.push_back(std::filesystem::is_regular_file(dir + "/" + s.file.substr(0, s.file.rfind('.')) + ".csv"));
    return run;
  };
  // (Read only where checkpoints are written: a mesh is hashed whole.)
  const RunIdentity id = scene.output.checkpoint_every > 0 ? run_identity(p) : RunIdentity{};
  if (scene.load_path()) {
    const ModelHistory* history = p.physics().history();
    const std::size_t history_values = history ? history->values_per_particle() : 0;
    const LoadPathState state = restart ? io::load_path_state(restart->checkpoint(), dofs, history_values) : LoadPathState{};
    return run_load_path(p, dir, u, series, probes, last_snapshot,
                         checkpoint_writer<LoadPathState>(dir, p, id, progress_now), restart ? &state : nullptr);
  }
  // ADR snapshots are stamped with the iteration, Verlet snapshots with the time (s).
  const bool dynamic = solver_of(scene).dynamic;
  TerminalProgress terminal(scene.solver.type.c_str());
  HistoryAsItGoes progress(terminal, dir + "/history.csv");
  SolveHooks hooks;
  hooks.progress = &progress;
  hooks.observe = {scene.output.vtk_every, [&](std::int64_t it, double t, const std::vector<double>& state) {
                     add_snapshot(series, dynamic ? t : double(it), p, state, dir);
                     last_snapshot = it;
                   }};
  hooks.adr_checkpoints = checkpoint_writer<AdrState>(dir, p, id, progress_now);
  hooks.verlet_checkpoints = checkpoint_writer<VerletState>(dir, p, id, progress_now);
  // The resumed state of the checkpoint's solver (Restart checked it is the scene's).
  std::optional<AdrState> adr;
  std::optional<VerletState> verlet;
  if (restart && checkpoint_solver(scene) == "adr") adr = io::adr_state(restart->checkpoint(), dofs);
  if (restart && checkpoint_solver(scene) == "verlet") verlet = io::verlet_state(restart->checkpoint(), dofs);
  hooks.adr_resume = adr ? &*adr : nullptr;
  hooks.verlet_resume = verlet ? &*verlet : nullptr;
  return solve_problem(p, u, hooks);
}

}  // namespace

SolveReport solve_scene(Problem& p, const std::string& dir, std::vector<double>& u, io::PvdSeries& series,
                        ProbeHistory& probes, std::int64_t& last_snapshot, const Restart* restart) {
  if (restart) {
    series.resume(restart->progress().snapshots);
    // The series' file now, not at the next snapshot: a path checkpointed at its last step
    // has none to come, and resumed without NAME.pvd (in place, its own was removed).
    if (!series.steps().empty()) series.write();
    last_snapshot = restart->progress().last_snapshot;
    probes.rows = restart->progress().probe_rows;
    if (const auto& path = restart->progress().stress_path; path.size() == 2) probes.stress = {path[0], path[1]};
  }
  try {
    return solve(p, dir, u, series, probes, last_snapshot, restart);
  } catch (const std::invalid_argument& e) {
    // The solvers refuse a state that does not fit them; from a checkpoint that is bad input.
    if (!restart) throw;
    throw InputError("--restart: " + restart->where() + " does not fit the scene: " + e.what());
  }
}

}  // namespace perinom::cli
