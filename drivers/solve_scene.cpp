#include "solve_scene.hpp"

#include <stdexcept>

#include "perinom/core/error.hpp"
#include "perinom/solvers/newton.hpp"
#include "perinom/solvers/verlet.hpp"
#include "run_checkpoint.hpp"
#include "snapshot.hpp"
#include "terminal_progress.hpp"

namespace perinom::cli {

NewtonOptions newton_options(const SolverSpec& s) {
  NewtonOptions o;
  o.load_steps = s.load_steps;
  o.line_search = s.line_search;
  o.step_tolerance = s.step_tolerance;
  if (s.type == "newton") o.tolerance = s.tolerance, o.max_iterations = static_cast<int>(s.max_iterations);
  return o;
}

namespace {

SolveReport solve(Problem& p, const std::string& dir, std::vector<double>& u, io::PvdSeries& series,
                  ProbeHistory& probes, std::int64_t& last_snapshot, const Restart* restart) {
  const Scene& scene = p.scene;
  const std::size_t dofs = p.physics().dofs();
  // What a checkpoint holds beside the solver's state, as it is when the checkpoint is due.
  const auto progress_now = [&] { return RunProgress{series.steps(), last_snapshot, probes.rows}; };
  if (scene.load_path()) {
    const LoadPathState state = restart ? load_path_state(restart->checkpoint(), dofs) : LoadPathState{};
    return run_load_path(p, dir, u, series, probes, last_snapshot,
                         checkpoint_writer<LoadPathState>(dir, p, progress_now), restart ? &state : nullptr);
  }
  // ADR snapshots are stamped with the iteration, Verlet snapshots with the time (s).
  const bool dynamic = scene.solver.type == "verlet";
  Observer observe{scene.output.vtk_every, [&](std::int64_t it, double t, const std::vector<double>& state) {
                     add_snapshot(series, dynamic ? t : double(it), p, state, dir);
                     last_snapshot = it;
                   }};
  TerminalProgress progress(scene.solver.type.c_str());
  if (scene.solver.type == "adr") {
    AdrOptions o;
    o.tolerance = scene.solver.tolerance;
    o.displacement_tolerance = scene.solver.displacement_tolerance;
    o.max_iterations = scene.solver.max_iterations;
    o.load_steps = scene.solver.load_steps;
    o.history_every = scene.solver.history_every;
    const AdrState state = restart ? adr_state(restart->checkpoint(), dofs) : AdrState{};
    return solve_adr(p.physics(), p.loading, o, u, &progress, observe,
                     checkpoint_writer<AdrState>(dir, p, progress_now), restart ? &state : nullptr);
  }
  if (scene.solver.type == "newton") return solve_newton(p.physics(), p.loading, newton_options(scene.solver), u, &progress);
  VerletOptions o;
  o.dt = scene.solver.dt;
  o.safety = scene.solver.safety;
  o.steps = scene.solver.steps;
  o.ramp_time = scene.solver.ramp_time;
  o.history_every = scene.solver.history_every;
  o.energy_check = scene.solver.energy_check;
  o.energy_tolerance = scene.solver.energy_tolerance;
  const VerletState state = restart ? verlet_state(restart->checkpoint(), dofs) : VerletState{};
  std::vector<double> v;
  return solve_verlet(p.physics(), p.loading, o, u, v, &progress, observe,
                      checkpoint_writer<VerletState>(dir, p, progress_now), restart ? &state : nullptr);
}

}  // namespace

SolveReport solve_scene(Problem& p, const std::string& dir, std::vector<double>& u, io::PvdSeries& series,
                        ProbeHistory& probes, std::int64_t& last_snapshot, const Restart* restart) {
  if (restart) {
    series.resume(restart->progress().snapshots);
    last_snapshot = restart->progress().last_snapshot;
    probes.rows = restart->progress().probe_rows;
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
