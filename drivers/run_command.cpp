// perinom run: read a scene, build it, solve it, write VTK, CSV and summary.json.
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>

#include "commands.hpp"
#include "perinom/core/error.hpp"
#include "perinom/io/csv_writer.hpp"
#include "perinom/io/json_writer.hpp"
#include "perinom/io/vtk_writer.hpp"
#include "perinom/models/correspondence.hpp"
#include "perinom/models/model_history.hpp"
#include "perinom/scene/registry.hpp"
#include "perinom/solvers/adr.hpp"
#include "perinom/core/timer.hpp"
#include "perinom/solvers/newton.hpp"
#include "diagnostics.hpp"
#include "difference.hpp"
#include "damaged_newton_check.hpp"
#include "load_path_run.hpp"
#include "locking_warning.hpp"
#include "memory_estimate.hpp"
#include "output_folder.hpp"
#include "refused_run.hpp"
#include "reactions_output.hpp"
#include "small_strain_check.hpp"
#include "run_output.hpp"
#include "restart.hpp"
#include "snapshot.hpp"
#include "solve_scene.hpp"
#include "stability_check.hpp"
#include "support_check.hpp"
#include "terminal_progress.hpp"

namespace perinom::cli {
namespace {

namespace fs = std::filesystem;
using io::Json;
using io::write_json_file;

/// Probe values into the summary; line probes also into probe_NAME.csv. Prints the point
/// probes' values.
Json probe_results(const Problem& p, const std::vector<double>& u, const std::string& dir) {
  const ProbeReadout readout(p, u);
  Json out = Json::object();
  for (const auto& probe : p.probes) {
    if (!probe.spec.is_line) {
      const double v = readout.point(probe);
      if (!std::isfinite(v)) throw SolveError("probe '" + probe.spec.name + "': its value is NaN or Inf");
      out[probe.spec.name] = v;
      std::printf("  %s = %.6e\n", probe.spec.name.c_str(), v);
      continue;
    }
    const std::string file = "probe_" + probe.spec.name + ".csv";
    io::CsvWriter csv(dir + "/" + file);
    csv.header(readout.line_header(probe.spec));
    for (std::size_t k = 0; k < probe.particles.size(); ++k) {
      const std::vector<double> row = readout.line_row(probe, k);
      for (const double x : row)
        if (!std::isfinite(x)) throw SolveError("probe '" + probe.spec.name + "': a value is NaN or Inf");
      csv.row(row);
    }
    csv.close();
    Json j = Json::object();
    j["file"] = file;
    j["points"] = probe.particles.size();
    out[probe.spec.name] = j;
  }
  return out;
}

/// The note on particles that lost a family spanning the plane (space): by broken bonds or
/// precracks; `softening` when softening bonds still hold them.
void note_detached(std::int64_t detached, int dim, bool softening) {
  if (detached > 0)
    note("%lld particle(s) lost a family that spans the %s and were detached: they carry no "
         "stress and %s (summary.json solver.fracture.detached_particles)",
         static_cast<long long>(detached), dim == 2 ? "plane" : "space",
         softening ? "only their softening bonds hold them" : "move freely");
}

/// solver.check: newton. Solves again with Newton and reports how far apart the answers are.
Json newton_check(Problem& p, const std::vector<double>& u) {
  std::vector<double> un;
  const double t0 = wall_seconds();
  TerminalProgress progress("newton check");
  const SolveReport rep = solve_newton(p.physics(), p.loading, newton_options(p), un, &progress);
  const double seconds = wall_seconds() - t0;
  // The model's stress measure (a plate's: its bending moments).
  const std::vector<double> s = p.physics().stress_measure(u.data()), sn = p.physics().stress_measure(un.data());
  const Difference du = difference(u, un), ds = difference(s, sn);
  Json j = check_json(du, ds, rep, seconds);
  std::printf("perinom: Newton check: displacement differs by %.3e, stress by %.3e (relative L2); "
              "Newton: %lld iterations, %.3f s\n", du.relative_l2, ds.relative_l2, static_cast<long long>(rep.iterations), seconds);
  warn_if_apart(du, ds, rep);
  return j;
}

/// The scene's particles, families and operators, saying what was built.
Problem build(const Options& opt, const Scene& scene, PhaseTimer& timer) {
  std::printf("perinom: %s: building particles, families and operators\n", scene.name.c_str());
  std::fflush(stdout);
  Problem p = build_problem(scene, &timer);
  p.memory_limit = opt.max_memory;
  std::printf("perinom: %s: %zu particles, %zu bonds, %d threads, solver %s\n", scene.name.c_str(),
              p.cloud.size(), p.bonds, omp_get_max_threads(), scene.solver.type.c_str());
  return p;
}

int run_in_folder(const Scene& scene, const MemoryEstimate& estimate,
                  const std::optional<Restart>& restart, const std::string& dir, PhaseTimer& timer, Problem& p) {
  if (restart) {
    restart->bring_snapshots(dir);
    std::printf("perinom: resuming from %s\n", restart->where().c_str());
  }
  if (scene.model.kinematics == "finite_rotation" &&
      scene.any_boundary([](const BoundarySpec& b) { return b.traction || b.pressure; }))
    note("model.kinematics finite_rotation: %s",
                scene.model.follower_pressure
                    ? "pressures follow the deformed surface; traction vectors stay dead loads (reference area)"
                    : "tractions and pressures stay nominal (model.follower_pressure: false)");
  print_body_notes(p);
  if (scene.damage && scene.damage->fracture_energy > 0.0)
    note("damage.fracture_energy: the broken bonds dissipate G_f per unit crack area; a "
                "notched beam's peak still moved 2.7%% over a halving of the spacing at horizon 3.015 dx "
                "(1.363, 1.334, 1.327 kN at 2.5, 1.786, 1.25 mm; docs/verification/notched_beam.md): compare two "
                "spacings");
  const Json pins = pin_results(p);
  std::fflush(stdout);
  const bool dynamic = solver_of(scene).dynamic;
  bool free_motion = false;
  if (!dynamic) warn_if_unstable(p), free_motion = warn_if_free(p);
  else if (scene.solver.allow_unstable &&
           (scene.model.formulation == "improved" || scene.model.formulation == "strong"))
    warn("model.formulation %s in explicit dynamics (solver.allow_unstable): "
                 "non-symmetric, its energy may grow without bound; the energy-balance guard %s",
                 scene.model.formulation.c_str(), scene.solver.energy_check ? "stops the run if it does" : "is off");
  // An example's steps shortened by --set keep its damage.every: warned, not refused (as
  // output.vtk_steps beyond a load path). Bonds are looked at every `every` steps only.
  if (dynamic && scene.damage && scene.damage->every > scene.solver.steps)
    warn("damage.every = %lld is beyond solver.steps = %lld: no step looks for bonds to break, and none breaks",
         static_cast<long long>(scene.damage->every), static_cast<long long>(scene.solver.steps));

  io::PvdSeries series(dir, scene.name);
  std::vector<double> u(p.physics().dofs(), 0.0);
  std::int64_t last_snapshot = -1;
  ProbeHistory probe_history;
  timer.start("solve");
  const SolveReport rep = solve_scene(p, dir, u, series, probe_history, last_snapshot, restart ? &*restart : nullptr);
  const std::string& failure = rep.failure;
  timer.start("output");
  const std::int64_t steps_done = static_cast<std::int64_t>(rep.history.rows());
  // The final state: after a divergence the last state that passed the guard. A snapshot
  // whose fields are not finite is refused (snapshot.hpp); then neither it nor the probes'
  // files are written, and the summary says why.
  std::string final_state_error;
  Json probes;
  try {
    if (scene.load_path()) {
      if (last_snapshot != steps_done || (!failure.empty() && !rep.diverged))
        add_snapshot(series, double(steps_done), p, u, dir);
      probe_history.write(p, dir);
    } else if (last_snapshot != rep.iterations) {
      add_snapshot(series, dynamic ? rep.end_time : double(rep.iterations), p, u, dir);
    }
    probes = probe_results(p, u, dir);
  } catch (const SolveError& e) {
    final_state_error = e.what();
    std::fprintf(stderr, "perinom: the final state is not written: %s\n", e.what());
  }
  write_history(dir + (scene.load_path() ? "/load_steps.csv" : "/history.csv"), rep.history);
  const bool converged = failure.empty() && rep.converged && final_state_error.empty();
  Json summary = Json::object();
  summary["status"] = rep.diverged || !final_state_error.empty() ? "diverged" : converged ? "converged" : "not_converged";
  summary["scene"] = scene.source;
  summary["name"] = scene.name;
  summary["dimension"] = scene.dim;
  summary["particles"] = p.cloud.size();
  summary["bonds"] = p.bonds;
  summary["threads"] = omp_get_max_threads();
  if (restart) summary["restarted_from"] = restart->where();
  if (!p.pins.empty()) {
    Json constraints = Json::object();
    constraints["rigid_body"] = pins;
    summary["constraints"] = constraints;
  }
  Json solver = Json::object();
  solver["type"] = scene.solver.type;
  solver["iterations"] = static_cast<long long>(rep.iterations);
  solver["converged"] = converged;
  solver["residual"] = rep.residual;
  solver["displacement_change"] = rep.displacement_change;
  add_rounding_floor(rep, solver);
  if (scene.load_path()) solver["load_steps"] = static_cast<long long>(steps_done);
  if (dynamic) {
    solver["stable_time_step"] = rep.stable_time_step;
    solver["end_time"] = rep.end_time;
    add_energy_balance(rep.history, solver);
    add_ramp_reached(scene.solver.ramp_time, rep.end_time, solver);
  }
  if (scene.damage && rep.iterations > 0) {
    // The cost of breaking: a step that looks (find) and one that breaks, against an intact
    // step (the rest of the loop), in seconds and as ratios.
    const auto& c = rep.changes;
    const double steps = double(rep.iterations);
    const double intact = (c.loop_seconds - c.find_seconds - c.change_seconds) / steps;
    const double find = c.find_seconds / steps;
    const double change = c.changing_steps > 0 ? c.change_seconds / double(c.changing_steps) : 0.0;
    Json f = Json::object();
    if (scene.damage->criterion == "stretch") f["s_c"] = p.scene.damage->s_c;  // given, or from G_c
    f["breaking_steps"] = static_cast<long long>(c.changing_steps);
    f["bonds_broken"] = static_cast<long long>(c.broken);
    f["detached_particles"] = static_cast<long long>(c.detached);
    if (c.spent >= 0) f["softening_bonds_spent"] = static_cast<long long>(c.spent), f["opening_limit"] = c.opening_limit;
    note_detached(c.detached, scene.dim, c.spent >= 0);
    if (dynamic) f["time_step_reductions"] = static_cast<long long>(c.step_reductions), f["final_time_step"] = c.final_dt;
    if (c.step_reductions > 0)
      note("broken bonds lowered the stable time step %lld time(s); the run kept its ratio to "
                  "it and ended at dt = %.4g s (summary.json solver.fracture.final_time_step)",
                  static_cast<long long>(c.step_reductions), c.final_dt);
    if (c.armed_step >= 0) {
      f["armed_step"] = static_cast<long long>(c.armed_step);
      f["hourglass_threshold"] = c.hourglass_threshold;
      note("the instability criterion armed at step %lld (a bond reached s_max); from then on "
                  "bonds whose hourglass strain exceeds s_hg_max = %.4g break (summary.json solver.fracture.armed_step)",
                  static_cast<long long>(c.armed_step), c.hourglass_threshold);
    }
    if (dynamic) {  // a load path's cost is in load_steps.csv, step by step
      f["intact_step_seconds"] = intact;
      f["find_seconds_per_step"] = find;
      f["break_seconds_per_breaking_step"] = change;
      f["looking_step_ratio"] = intact > 0.0 ? (intact + find) / intact : 0.0;
      f["breaking_step_ratio"] = intact > 0.0 ? (intact + find + change) / intact : 0.0;
    }
    solver["fracture"] = f;
  } else if (!scene.damage && !scene.precracks.empty()) {
    // What the precracks detached: loaded, such particles fly off, and the run said nothing.
    Json f = Json::object();
    const auto detached = static_cast<std::int64_t>(p.as<CorrespondenceModel>().G().detached().size());
    f["detached_particles"] = static_cast<long long>(detached);
    note_detached(detached, scene.dim, false);
    solver["fracture"] = f;
  }
  if (rep.diverged) {
    solver["diverged_at"] = static_cast<long long>(rep.diverged_at);
    solver["last_good"] = static_cast<long long>(scene.load_path() ? steps_done : rep.iterations);
  }
  if (!failure.empty()) solver["error"] = failure;
  if (!final_state_error.empty()) solver["final_state_error"] = final_state_error;
  if (!rep.unstable_end.empty()) {
    solver["unstable_end"] = rep.unstable_end;
    warn("the converged end state is %s (summary.json solver.unstable_end): a disturbance leaves it, so the "
         "body would not stay there", rep.unstable_end.c_str());
  }
  summary["solver"] = solver;
  if (failure.empty()) {
    // The final state's load factor: 1, or Verlet's ramp where the run ended.
    const double s_end = dynamic && scene.solver.ramp_time > 0.0 ? std::min(1.0, rep.end_time / scene.solver.ramp_time) : 1.0;
    const double carried = scene.load_path() ? largest_reaction_carried(rep.history) : 0.0;
    add_reaction_results(p.physics(), scene.load_path() ? p.stages.back().loading : p.loading, s_end, u, dynamic, summary,
                         carried, rep.at_rounding_floor ? rep.stiffness_force : 0.0);
    check_small_strain(p, u, summary);
  }
  if (scene.solver.check == "newton" && failure.empty()) {
    timer.start("newton check");
    // A check Newton refuses (InputError: a singular stiffness, a support missing; a factor
    // over --max-memory) is the check's failure, not the run's: it once ended the run with
    // exit 2 and a summary that had lost the solve's record.
    try {
      summary["check"] = !scene.load_path() ? newton_check(p, u)
                         : scene.damage  ? damaged_newton_check(p, u, probe_history.stress)
                                         : load_path_newton_check(p, u, probe_history);
    } catch (const InputError& e) {
      Json check = Json::object();
      check["newton_converged"] = false;
      check["newton_error"] = e.what();
      summary["check"] = check;
      warn("solver.check: newton could not solve: %s (summary.json check.newton_error)", e.what());
    }
    timer.start("output");
  }
  if (const ModelHistory* history = p.physics().history()) summary["plasticity"] = plastic_summary(p.physics(), *history);
  summary["probes"] = probes;
  timer.stop();
  Json wall = Json::object();
  for (const auto& ph : timer.phases()) wall[ph.first] = ph.second;
  summary["wall_time"] = wall;
  Json memory = Json::object();
  memory["estimated_bytes"] = estimate.bytes;
  memory["peak_bytes"] = peak_resident_bytes();
  summary["memory"] = memory;
  // Last, so a summary.json beside the marker-free folder means the run ended here.
  add_diagnostics(summary);
  write_json_file(dir + "/summary.json", summary);

  if (!final_state_error.empty() && failure.empty()) throw SolveError(final_state_error);
  // A load step that did not balance (ADR's max_iterations, or solver.max_rounds) leaves the
  // path not converged, as ADR alone would: exit 1. Divergence and Newton failures: exit 3.
  if (!failure.empty() && scene.load_path() && !rep.diverged && scene.solver.type != "newton") {
    std::fprintf(stderr, "perinom: NOT converged: %s%s; the last balanced state and results in %s\n", failure.c_str(),
                 free_motion ? " (the supports leave a rigid motion free: the warning at the start names it)" : "",
                 dir.c_str());
    if (scene.damage) explain_free_pieces(p, rep.history);
    return 1;
  }
  if (!failure.empty()) throw SolveError(failure + "; results in " + dir);
  if (dynamic)
    std::printf("perinom: %lld steps to t = %.6e s (stable step %.3e s); results in %s\n",
                static_cast<long long>(rep.iterations), rep.end_time, rep.stable_time_step, dir.c_str());
  else if (scene.load_path())
    std::printf("perinom: %lld load steps, %lld %s iterations in all; results in %s\n",
                static_cast<long long>(steps_done), static_cast<long long>(rep.iterations),
                solver_of(scene).iterations_of.c_str(), dir.c_str());
  else
    std::printf("perinom: %s after %lld iterations (%s); results in %s\n",
                rep.converged ? "converged" : "NOT converged", static_cast<long long>(rep.iterations),
                residual_text(rep).c_str(), dir.c_str());
  return rep.converged ? 0 : 1;
}

}  // namespace

int run(const Options& opt) {
  if (opt.positional.size() != 1) throw InputError("run needs exactly one scene file");
  PhaseTimer timer;
  // Until the folder is prepared, a refusal leaves it alone unless it holds an earlier run
  // (refused_run.hpp); the folder a --restart resumes in place is always left alone.
  RefusedRun refused(opt.positional[0], opt.restart);
  if (!opt.out.empty()) refused.folder(opt.out, "");
  return refused.recording([&]() -> int {
    timer.start("read scene");
    const Scene scene = read_scene(opt.positional[0], opt.overrides);
    // --restart DIR continues in DIR unless --out names another folder.
    const std::string dir = !opt.out.empty() ? opt.out : !opt.restart.empty() ? opt.restart : "out/" + scene.name;
    refused.folder(dir, scene.name);
    const MemoryEstimate estimate = estimate_memory(scene);
    require_memory(scene, estimate, opt.max_memory > 0.0 ? opt.max_memory : available_memory(), opt.max_memory > 0.0);
    // The checkpoint is checked against the scene before anything is built.
    const std::optional<Restart> restart =
        opt.restart.empty() ? std::nullopt : std::optional<Restart>(std::in_place, opt.restart, scene);
    const bool in_place = restart && restart->in_place(dir);
    const auto in_folder = [&](Problem* built) -> int {
      refused.leave_folder();
      const RunFolder folder(dir, opt.keep, in_place ? restart->files() : std::set<std::string>{},
                             [&scene](const std::string& name) { return scene_writes(scene, name); });
      folder.announce();
      return folder.recording_errors(scene, [&] {
        if (built) return run_in_folder(scene, estimate, restart, dir, timer, *built);
        Problem p = build(opt, scene, timer);
        return run_in_folder(scene, estimate, restart, dir, timer, p);
      });
    };
    if (!restart) return in_folder(nullptr);
    // A restart is checked whole, its particles too, before its folder is touched: refused
    // once the folder was cleaned in place, it had removed the results of the run it resumes.
    Problem p = build(opt, scene, timer);
    restart->check(p);
    return in_folder(&p);
  });
}

}  // namespace perinom::cli
