// mpirun -np R perinom run SCENE (issue 19). The particles are split into R blocks along the
// Morton curve; each rank builds the families and operators of its local part (owned, then
// the ghosts within two horizons) and runs the serial ADR, Verlet or load path (stages, LBC)
// on its owned dofs through DistributedModel (one halo exchange of u per force, the solvers'
// sums over the ranks, a plastic law's states shared with the ghosts after each commit),
// or Newton through PETSc SNES with its Jacobian assembled over the ranks (mumps or gamg).
// Rank 0 prints and writes the history, the probes and summary.json; every rank writes its
// piece of each snapshot. Partial, and refused otherwise, naming the key: correspondence
// scenes of the classical or consistent formulation on a lattice or a body from files (the
// consistent correction solved over the ranks), radius or k-nearest families (the latter
// searched on the whole cloud), small strain or finite rotation (no follower pressure), elastic or
// Drucker-Prager, constraints on their particles or at the face (Galerkin, their multipliers
// solved over the ranks: Loading::ranks), `constraints: rigid_body` (pinned on the whole
// cloud), tractions and pressures, adr, verlet, newton (mumps, or gamg with constraints on
// their particles only), or a load path by adr, lbc or newton. Every rank
// builds the whole cloud and loading (O(N) memory per rank) to choose its part. Thin plates
// (radius families): each rank's plate is its part's nodes and their mirror ghosts
// (plate_part.hpp), fitted at its owned and near nodes.
#include <omp.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <optional>
#include <set>

#include "commands.hpp"
#include "diagnostics.hpp"
#include "distributed_output.hpp"
#include "locking_warning.hpp"
#include "memory_estimate.hpp"
#include "output_folder.hpp"
#include "refused_run.hpp"
#include "perinom/core/error.hpp"
#include "perinom/operators/singular_family.hpp"
#include "perinom/core/timer.hpp"
#include "perinom/distributed/loading_share.hpp"
#include "perinom/distributed/correction_share.hpp"
#include "perinom/distributed/local_loading.hpp"
#include "perinom/neighbors/partition.hpp"
#include "perinom/neighbors/search.hpp"
#include "perinom/scene/rank_loading.hpp"
#include "perinom/scene/plate_part.hpp"
#include "perinom/scene/registry.hpp"
#include "perinom/solvers/adr.hpp"
#include "perinom/solvers/newton.hpp"
#include "perinom/solvers/verlet.hpp"
#include "rank_load_path.hpp"
#include "rank_newton.hpp"
#include "rank_memory.hpp"
#include "rank_rigid_body.hpp"
#include "reactions_output.hpp"
#include "small_strain_check.hpp"
#include "support_check.hpp"
#include "run_output.hpp"
#include "terminal_progress.hpp"

namespace perinom::cli {
namespace {

/// Refuses, naming the key, what the distributed run does not do yet.
void require_distributed(const Scene& s, const Options& opt) {
  auto refuse = [&](const std::string& key, const std::string& what) {
    throw InputError(s.source + ": " + key + ": " + what +
                     " is not distributed yet (mpirun -np R perinom run distributes correspondence scenes of the "
                     "classical or consistent formulation on a box or a body from files, elastic or drucker_prager at "
                     "small strain or finite rotation, solved by adr, verlet or newton (mumps or gamg), or in load steps and stages by adr, "
                     "lbc or newton, with constraints on their particles or at the face or rigid_body, tractions and pressures; and "
                     "thin plates with radius families); run it without mpirun");
  };
  if (!opt.restart.empty()) refuse("--restart", "a restart");
  if (s.model.type != "correspondence" && s.model.type != "thin_plate") refuse("model.type", s.model.type);
  // A thin plate's k nearest would be searched among its mirror ghosts on the whole plate.
  if (s.model.type == "thin_plate" && s.discretization.horizon_neighbors > 0)
    refuse("discretization.horizon", "a thin_plate with k-nearest families");
  // Finite rotation is pointwise (the law's polar decomposition); a follower pressure is not
  // (its force and tangent act on the ranks' facets otherwise than serially: the biaxial
  // example's reactions differed by 0.2%).
  if (s.model.kinematics == "finite_rotation" && s.model.follower_pressure &&
      s.any_boundary([](const BoundarySpec& b) { return b.pressure.has_value(); }))
    refuse("model.follower_pressure", "a follower pressure (finite_rotation turns pressures with the surface; "
           "follower_pressure: false keeps them in the reference configuration)");
  if (s.model.type == "correspondence" && s.model.formulation != "classical" && s.model.formulation != "consistent")
    refuse("model.formulation", "the " + s.model.formulation + " formulation (its strong rows read the whole body)");
  if (s.solver.type != "adr" && s.solver.type != "verlet" && s.solver.type != "newton" &&
      !(s.solver.type == "lbc" && s.load_path()))
    refuse("solver.type", s.solver.type);
  if (s.damage) refuse("damage", "bond breaking");
  if (!s.precracks.empty()) refuse("precracks", "a precrack");
  if (s.solver.check != "none" && s.load_path()) refuse("solver.check", "the " + s.solver.check + " check of a load path");
  if (s.output.checkpoint_every > 0) refuse("output.checkpoint_every", "a checkpoint");
  // Refused here, once, before the build: met in the solver's set-up, every rank said it.
  if ((s.solver.type == "newton" || s.solver.check == "newton") && s.solver.linear_solver == "gamg" &&
      s.any_boundary([](const BoundarySpec& b) { return b.at_face; }))
    throw InputError(s.source + ": solver.linear_solver: gamg takes constraints on their particles only over MPI "
                     "ranks (a support at: face makes Newton's system a saddle point there): use mumps");
}

/// `phase()`, which every rank runs alike on the same input (reading the scene, building the
/// whole cloud). Its InputError is then every rank's: reported once (InputErrorOnEveryRank).
/// Met by some ranks only (their files differ), it is theirs, and ends every rank.
template <class Phase>
auto alike_on_ranks(const Ranks& world, Phase phase) {
  std::optional<decltype(phase())> result;
  std::string error;
  try {
    result.emplace(phase());
  } catch (const InputError& e) {
    error = e.what();
  }
  if (sum_over_ranks(error.empty() ? 0.0 : 1.0) == double(world.size)) throw InputErrorOnEveryRank(error);
  if (!error.empty()) throw InputError(error);
  return std::move(*result);
}

int run_in_folder(const Options& opt, Scene& scene, const Ranks& world, const std::string& dir, PhaseTimer& timer);

}  // namespace

int run_distributed(const Options& opt) {
  if (opt.positional.size() != 1) throw InputError("run needs exactly one scene file");
  const Ranks world = mpi_ranks();
  const bool root = world.rank == 0;
  // One report: rank 0's (errors still reach stderr from every rank).
  if (!root && !std::freopen("/dev/null", "w", stdout)) throw InputError("cannot silence rank " + std::to_string(world.rank));
  PhaseTimer timer;
  timer.start("read scene");
  // Refused while reading, an earlier run's folder gets rank 0's error summary (refused_run.hpp),
  // not the one --restart names (the ranks refuse restarts): `--restart out/s --out out/s`
  // had emptied it.
  RefusedRun refused(opt.positional[0], opt.restart);
  if (root) refused.folder(opt.out, "");
  Scene scene = refused.recording([&] {
    return alike_on_ranks(world, [&] {
      Scene s = read_scene(opt.positional[0], opt.overrides);
      require_distributed(s, opt);
      return s;
    });
  });
  const std::string serial = scene.solver.linear_solver;
  if ((scene.solver.type == "newton" || scene.solver.check == "newton") && (serial == "klu" || serial == "umfpack")) {
    // KLU and UMFPACK factor on one process; MUMPS is the direct solver over the ranks (the
    // same Newton steps to rounding).
    scene.solver.linear_solver = "mumps";
    std::printf("perinom: solver.linear_solver: %s factors on one process; over %d ranks Newton's linear solver "
                "is mumps\n", serial.c_str(), world.size);
  }
  const std::string dir = !opt.out.empty() ? opt.out : "out/" + scene.name;
  std::optional<RunFolder> folder;
  if (root) {
    folder.emplace(dir, opt.keep, std::set<std::string>{},
                   [&scene](const std::string& name) { return scene_writes(scene, name); });
    folder->announce();
  }
  // An error after this is said in rank 0's summary.json (an error every rank meets ends them
  // on their own; one rank's ends all of them by MPI_Abort, before any summary).
  const auto body = [&] { return run_in_folder(opt, scene, world, dir, timer); };
  return folder ? folder->recording_errors(scene, body) : body();
}

namespace {

int run_in_folder(const Options& opt, Scene& scene, const Ranks& world, const std::string& dir, PhaseTimer& timer) {
  const bool root = world.rank == 0;
  barrier();
  std::printf("perinom: %s: building particles, families and operators on %d ranks\n", scene.name.c_str(), world.size);
  std::fflush(stdout);

  // The whole cloud's frame, this rank's part, and the local problem over it.
  timer.start("discretization");
  const bool thin_plate = scene.model.type == "thin_plate";
  std::optional<PlateFrame> plate;  // a thin plate's whole plate (its physical nodes are the frame's cloud)
  if (thin_plate) plate.emplace(alike_on_ranks(world, [&] { return plate_frame(scene); }));
  // (plate->problem is spent)
  const Problem frame = thin_plate ? std::move(plate->problem) : alike_on_ranks(world, [&] { return build_problem_frame(scene); });
  if (frame.cloud.size() < std::size_t(world.size))  // (a rank without particles crashed the search)
    throw InputErrorOnEveryRank(scene.source + ": " + std::to_string(frame.cloud.size()) + " particles for " +
                                std::to_string(world.size) + " ranks: every rank needs particles of its own; run on "
                                "fewer ranks (mpirun -np " + std::to_string(frame.cloud.size()) + " at most)");
  if (root) print_body_notes(frame);
  // The supports' free rigid motions, before a static solve, as serially (run_command.cpp):
  // on 2 ranks the run said nothing, and a load along one ended NOT converged with no reason.
  if (root && scene.solver.type != "verlet") warn_if_free_frame(frame, thin_plate ? &plate->plate : nullptr);
  const int d = frame.cloud.dim;
  // k-nearest families are searched on the whole cloud (the part's own search could break
  // the ties at the k-th distance otherwise), and the part reaches their largest support.
  const bool nearest = scene.discretization.horizon_neighbors > 0;
  Families whole = nearest ? scene_families(scene, frame.cloud) : Families{};
  const double horizon = nearest ? *std::max_element(whole.support.begin(), whole.support.end())
                                 : scene.discretization.horizon_ratio * scene.discretization.dx;
  const LocalPart part = local_part(frame.cloud, morton_order(frame.cloud), world.size, world.rank, horizon);
  Problem local;
  local.scene = scene;
  local.memory_limit = opt.max_memory;  // a bound for each rank (rank_newton_options)
  local.cloud = subcloud(frame.cloud, part.particles);
  local.probes = frame.probes;  // their specs (the readout asks whether one reconstructs)
  std::optional<PlateCloud> local_plate;  // a thin plate's part: its nodes, then their mirrors
  if (thin_plate) local_plate.emplace(sub_plate(plate->plate, part.particles));
  const Families families = thin_plate ? plate_families(scene, *plate, *local_plate, part.owned + part.near)
                            : nearest  ? local_families(whole, part)
                                       : scene_families(scene, local.cloud);
  whole = Families{};
  const RankMemory estimate = require_rank_memory(scene, double(families.bonds()), double(families.particles()), opt.max_memory);
  timer.start("operators");
  // The consistent formulation: the facets of the owned and near particles (the rows that
  // are evaluated), and the correction solved over the ranks.
  const bool consistent = scene.model.formulation == "consistent";
  const CorrectionShare share = correction_share(part);
  const LocalFacets facets = local_facets(frame.facets, frame.groups, part, part.owned + part.near);
  if (thin_plate) {
    local.model = plate_part_model(scene, *plate, part, std::move(*local_plate), families);
  } else {
    CorrespondenceOptions copt = correspondence_options(scene);
    copt.ranks = &share;
    copt.fitted_rows = part.owned + part.near;  // the far ghosts' truncated families only lend values
    try {
      local.model = std::make_unique<CorrespondenceModel>(local.cloud, families, scene.material, copt, Surface{},
                                                          consistent ? facets.facets : BoundaryFacets{});
    } catch (const SingularFamily& e) {
      // As serially: the key, and the particle in the whole cloud's numbering (it read the
      // rank's own, without the key).
      throw InputError(horizon_error(scene, frame.cloud, e.with_index(part.particles[e.particle])));
    }
  }
  DistributedModel distributed(dynamic_cast<LocalModel&>(*local.model), part);
  const LoadingShare loading_share(part, d);
  // A thin plate's loading holds its nodes (w = 0) and presses them: the owned ones' share.
  auto loading_of = [&](const std::vector<BoundarySpec>& boundary, const Loading& whole_loading) {
    return thin_plate ? local_loading(whole_loading, part, 1)  // w alone
                      : rank_loading(scene, boundary, whole_loading, frame, part, local.cloud, local.as<CorrespondenceModel>(),
                                     facets, loading_share);
  };
  const Loading loading = loading_of(scene.boundary, frame.loading);
  std::vector<LoadStage> stages;  // a load path's, each stage's items coupled as `loading`'s
  for (std::size_t k = 0; k < frame.stages.size(); ++k)
    stages.push_back({frame.stages[k].name, frame.stages[k].steps, loading_of(stage_boundary(scene, k), frame.stages[k].loading)});
  if (!thin_plate) require_rigid_body_over_ranks(frame, part, families, local.cloud, loading, stages);
  const io::Json pins = pin_results(frame);  // printed by rank 0 only (the others' stdout is silenced)
  std::size_t owned_bonds = 0;
  for (std::size_t p = 0; p < part.owned; ++p) owned_bonds += std::size_t(families.end(p) - families.begin(p));
  const double bonds = sum_over_ranks(double(owned_bonds));
  const double ghosts = max_over_ranks(double(part.ghosts()) / double(std::max<std::size_t>(part.owned, 1)));
  std::printf("perinom: %s: %zu particles, %.0f bonds, %d ranks x %d threads (ghosts up to %.0f%% of a rank's own), "
              "solver %s\n", scene.name.c_str(), frame.cloud.size(), bonds, world.size, omp_get_max_threads(),
              100.0 * ghosts, scene.solver.type.c_str());
  std::fflush(stdout);

  // The solve, on the owned dofs.
  const RankRun run{frame, part, local, distributed, world.rank, world.size};
  const bool dynamic = scene.solver.type == "verlet";
  io::PvdSeries series(dir, scene.name);
  std::int64_t last_snapshot = -1;
  Observer observe{scene.output.vtk_every, [&](std::int64_t it, double t, const std::vector<double>& state) {
                     add_piece_snapshot(series, dynamic ? t : double(it), run, state, dir);
                     last_snapshot = it;
                   }};
  std::optional<TerminalProgress> progress;
  if (root) progress.emplace(scene.solver.type.c_str());
  Progress* shown = progress ? &*progress : nullptr;
  std::vector<double> u(distributed.dofs(), 0.0), v;
  ProbeHistory probe_history;
  timer.start("solve");
  const SolveReport rep =
      scene.load_path()               ? run_rank_load_path(run, distributed, stages, dir, u, series, probe_history, last_snapshot)
      : dynamic                       ? solve_verlet(distributed, loading, verlet_options(scene.solver), u, v, shown, observe)
      : scene.solver.type == "newton" ? solve_newton(distributed, loading, rank_newton_options(scene.solver, run), u, shown)
                                      : solve_adr(distributed, loading, adr_options(scene.solver), u, shown, observe);
  const std::int64_t steps_done = std::int64_t(rep.history.rows());  // a load path's

  // The final state, the history and the summary (rank 0).
  timer.start("output");
  std::string final_state_error;
  io::Json probes;
  try {
    if (scene.load_path()) {
      if (last_snapshot != steps_done || (!rep.failure.empty() && !rep.diverged))
        add_piece_snapshot(series, double(steps_done), run, u, dir);
      if (root) probe_history.write(frame, dir);
    } else if (last_snapshot != rep.iterations) {
      add_piece_snapshot(series, dynamic ? rep.end_time : double(rep.iterations), run, u, dir);
    }
    probes = distributed_probe_results(run, u, dir);
  } catch (const SolveError& e) {
    final_state_error = e.what();
    std::fprintf(stderr, "perinom: the final state is not written: %s\n", e.what());
  }
  if (root) write_history(dir + (scene.load_path() ? "/load_steps.csv" : "/history.csv"), rep.history);
  const bool converged = rep.failure.empty() && rep.converged && final_state_error.empty();
  io::Json summary = io::Json::object();
  summary["status"] = rep.diverged || !final_state_error.empty() ? "diverged" : converged ? "converged" : "not_converged";
  summary["scene"] = scene.source;
  summary["name"] = scene.name;
  summary["dimension"] = scene.dim;
  summary["particles"] = frame.cloud.size();
  summary["bonds"] = static_cast<long long>(bonds);
  summary["threads"] = omp_get_max_threads();
  summary["ranks"] = world.size;
  if (!frame.pins.empty()) {
    io::Json constraints = io::Json::object();
    constraints["rigid_body"] = pins;
    summary["constraints"] = constraints;
  }
  io::Json solver = io::Json::object();
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
  if (rep.diverged) {
    solver["diverged_at"] = static_cast<long long>(rep.diverged_at);
    solver["last_good"] = static_cast<long long>(scene.load_path() ? steps_done : rep.iterations);
  }
  if (!rep.failure.empty()) solver["error"] = rep.failure;
  if (!final_state_error.empty()) solver["final_state_error"] = final_state_error;
  summary["solver"] = solver;
  if (scene.solver.check == "newton" && rep.failure.empty() && final_state_error.empty()) {
    timer.start("newton check");
    summary["check"] = rank_newton_check(run, distributed, loading, u);
    timer.start("output");
  }
  if (rep.failure.empty()) {
    const double s_end = dynamic && scene.solver.ramp_time > 0.0 ? std::min(1.0, rep.end_time / scene.solver.ramp_time) : 1.0;
    add_reaction_results(distributed, scene.load_path() ? stages.back().loading : loading, s_end, u, dynamic, summary,
                         scene.load_path() ? largest_reaction_carried(rep.history) : 0.0,
                         rep.at_rounding_floor ? rep.stiffness_force : 0.0);
    check_small_strain_over_ranks(run, u, summary);
  }
  if (const ModelHistory* history = distributed.history()) summary["plasticity"] = plastic_summary(distributed, *history);
  summary["probes"] = probes;
  timer.stop();
  io::Json wall = io::Json::object();
  for (const auto& ph : timer.phases()) wall[ph.first] = max_over_ranks(ph.second);
  summary["wall_time"] = wall;
  io::Json memory = io::Json::object();
  memory["estimated_bytes_per_rank"] = estimate.most_bytes;
  memory["peak_bytes_per_rank"] = max_over_ranks(double(peak_resident_bytes()));
  memory["peak_bytes_all_ranks"] = sum_over_ranks(double(peak_resident_bytes()));
  summary["memory"] = memory;
  add_diagnostics(summary);
  if (root) io::write_json_file(dir + "/summary.json", summary);
  barrier();

  if (!final_state_error.empty() && rep.failure.empty()) throw SolveError(final_state_error);
  // As a serial run: a load step that did not balance leaves the path not converged (exit 1);
  // Newton's failed solve is a solve failure (exit 3: it was said NOT converged, exit 1).
  // The solvers decide on values summed over the ranks: rep.failure is every rank's alike,
  // said once.
  if (!rep.failure.empty() && scene.load_path() && !rep.diverged && scene.solver.type != "newton") {
    if (root)
      std::fprintf(stderr, "perinom: NOT converged: %s; the last balanced state and results in %s\n", rep.failure.c_str(),
                 dir.c_str());
    return 1;
  }
  if (!rep.failure.empty()) throw SolveErrorOnEveryRank(rep.failure + "; results in " + dir);
  if (dynamic)
    std::printf("perinom: %lld steps to t = %.6e s (stable step %.3e s) on %d ranks; results in %s\n",
                static_cast<long long>(rep.iterations), rep.end_time, rep.stable_time_step, world.size, dir.c_str());
  else if (scene.load_path())
    std::printf("perinom: %lld load steps, %lld %s iterations in all on %d ranks; results in %s\n",
                static_cast<long long>(steps_done), static_cast<long long>(rep.iterations),
                solver_of(scene).iterations_of.c_str(), world.size, dir.c_str());
  else
    std::printf("perinom: %s after %lld iterations (%s) on %d ranks; results in %s\n",
                rep.converged ? "converged" : "NOT converged", static_cast<long long>(rep.iterations),
                residual_text(rep).c_str(), world.size, dir.c_str());
  return rep.converged ? 0 : 1;
}

}  // namespace

}  // namespace perinom::cli
