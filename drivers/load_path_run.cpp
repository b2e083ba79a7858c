#include "load_path_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "perinom/core/timer.hpp"
#include "perinom/io/csv_writer.hpp"
#include "diagnostics.hpp"
#include "difference.hpp"
#include "run_output.hpp"
#include "snapshot.hpp"
#include "terminal_progress.hpp"

namespace perinom::cli {
namespace {

constexpr int kProbeColumns = ProbeHistory::probe_columns;  // value, von_mises, mean_stress, equivalent_strain, eq_plastic_strain
constexpr int kStepColumns = 3;   // stage, step, load_factor
std::vector<const BoundProbe*> point_probes(const Problem& p) {
  std::vector<const BoundProbe*> out;
  for (const auto& probe : p.probes)
    if (!probe.spec.is_line) out.push_back(&probe);
  return out;
}

}  // namespace

void StepProgress::update(const ProgressSample& s) {
  constexpr double quiet_seconds = 10.0;
  if (s.step_converged) {  // (Newton: the step's own row follows)
    newton_base_ = -1;
    return;
  }
  if (s.target <= 0.0 && newton_base_ < 0) newton_base_ = s.iteration - 1;  // the step's first Newton iteration
  const double now = wall_seconds();
  if (now - last_line_ < quiet_seconds) return;
  if (s.target > 0.0)
    std::printf("  ... load step %d/%d still balancing: %lld iterations in it, residual %.3e (target %.1e), %.0f s\n",
                s.load_step, s.load_steps, static_cast<long long>(s.iteration), s.residual, s.target,
                now - step_start_);
  else  // Newton: no residual inside KINSOL's iterations
    std::printf("  ... load step %d/%d still solving: Newton iteration %lld, %.0f s\n", s.load_step, s.load_steps,
                static_cast<long long>(s.iteration - newton_base_), now - step_start_);
  std::fflush(stdout);
  last_line_ = now;
}

void StepProgress::phase(const char* what) {
  if (!phases_.insert(what).second) return;
  std::printf("perinom: %s\n", what);
  std::fflush(stdout);
}

void add_probe_values(const ProbeReadout& readout, const BoundProbe& probe, double* out) {
  const std::size_t i = probe.particles.at(0);
  out[0] = readout.point(probe);
  int k = 1;
  for (const char* field : {"von_mises", "mean_stress", "equivalent_strain", "eq_plastic_strain"})
    out[k++] = readout.scalar(field, i);
}

std::vector<double> ProbeHistory::step_columns(const LoadStepRecord& r) {
  return {double(r.stage), double(r.step), r.load_factor};
}

void ProbeHistory::record(const Problem& p, const LoadStepRecord& r, const std::vector<double>& u) {
  if (p.scene.damage && p.scene.solver.check == "newton") stress.add(p.physics().stress_measure(u.data()));
  const auto probes = point_probes(p);
  if (probes.empty()) return;
  const ProbeReadout readout(p, u);
  std::vector<double> row = step_columns(r);
  row.resize(kStepColumns + probes.size() * kProbeColumns);
  for (std::size_t k = 0; k < probes.size(); ++k) add_probe_values(readout, *probes[k], row.data() + kStepColumns + k * kProbeColumns);
  rows.push_back(row);
}

void print_load_path_plan(const Scene& scene, const std::vector<LoadStage>& stages, const LoadPathOptions& opt) {
  int total = 0;
  for (const auto& st : stages) total += st.steps;
  std::printf("perinom: %zu stage(s), %d load steps, %s\n", stages.size(), total,
              opt.scheme == LoadPathScheme::lbc ? "loading-balance-correction"
              : opt.scheme == LoadPathScheme::newton ? "Newton with the consistent tangent"
              : scene.plasticity                     ? "plain ADR, plastic update in every iteration"
                                                     : "ADR");
  if (opt.scheme == LoadPathScheme::every_iteration && scene.plasticity)
    warn("solver.type adr with material drucker_prager: plain ADR commits the return map in every iteration, so "
         "the overshoot of its balance yields particles the loads never yield (one load step to 90 kPa of "
         "confinement: 364 of 400 particles yielded and 34.4 kPa von Mises, where lbc and newton yield none and give "
         "45.0; examples/biaxial_compression.yaml in 1 + 1 load steps at dx = 6.25 mm: 161 kPa von Mises at its "
         "centre against 228); it is there for comparison: solver.type lbc (the default) or newton");
  std::string beyond;
  for (const std::int64_t step : scene.output.vtk_steps)
    if (step > total) beyond += (beyond.empty() ? "" : ", ") + std::to_string(step);
  if (!beyond.empty())  // an example's path shortened by --set keeps its snapshot list: warned, not refused
    warn("output.vtk_steps: load step(s) %s beyond the path's %d: no snapshot there",
                beyond.c_str(), total);
  std::printf("  %5s %5s %6s %10s %6s %8s %8s %8s %10s %8s%s\n", "stage", "step", "factor", "iterations",
              "rounds", "flagged", "yielding", "plastic", "residual", "seconds", scene.damage ? "   broken" : "");
}

void print_load_step(const Scene& scene, const LoadStepRecord& r) {
  std::printf("  %5d %5d %6.3f %10lld %6d %8zu %8zu %8zu %10.3e %8.3f", r.stage, r.step, r.load_factor,
              static_cast<long long>(r.iterations), r.rounds, r.newly_flagged, r.yielding, r.plastic,
              r.residual, r.seconds);
  if (scene.damage) std::printf(" %8zu", r.broken);
  std::printf("\n");
  std::fflush(stdout);
}

bool snapshot_due(const Scene& scene, std::int64_t done) {
  const auto& want = scene.output.vtk_steps;
  return std::find(want.begin(), want.end(), done) != want.end() ||
         (scene.output.vtk_every > 0 && done % scene.output.vtk_every == 0);
}

void ProbeHistory::write(const Problem& p, const std::string& dir) const {
  const auto probes = point_probes(p);
  for (std::size_t k = 0; k < probes.size(); ++k) {
    io::CsvWriter csv(dir + "/probe_" + probes[k]->spec.name + "_history.csv");
    // "value": the probe's own reading (a von_mises probe's header repeated von_mises).
    csv.header({"stage", "step", "load_factor", "value", "von_mises", "mean_stress",
                "equivalent_strain", "eq_plastic_strain"});
    for (const auto& row : rows) {
      std::vector<double> out(row.begin(), row.begin() + kStepColumns);
      const auto first = row.begin() + kStepColumns + k * kProbeColumns;
      out.insert(out.end(), first, first + kProbeColumns);
      csv.row(out);
    }
    csv.close();
  }
}

SolveReport run_load_path(Problem& p, const std::string& dir, std::vector<double>& u, io::PvdSeries& series, ProbeHistory& probes,
                          std::int64_t& last_snapshot, const Checkpoints<LoadPathState>& checkpoints,
                          const LoadPathState* resume) {
  const Scene& scene = p.scene;
  print_load_path_plan(scene, p.stages, load_path_options(scene.solver));
  std::int64_t done = resume ? steps_done(*resume, p.stages) : 0;  // load steps over all stages
  TableClock tables;
  StepProgress progress;
  auto after_step = [&](const LoadStepRecord& r, const std::vector<double>& u) {
    ++done;
    probes.record(p, r, u);
    if (r.rows && tables.due()) {
      const double started = wall_seconds();
      write_history(dir + "/load_steps.csv", *r.rows);  // a resumed path's rows include the checkpoint's
      probes.write(p, dir);
      tables.wrote(started);
    }
    print_load_step(scene, r);
    progress.step_done();
    if (snapshot_due(scene, done)) {
      add_snapshot(series, double(done), p, u, dir);
      last_snapshot = done;
    }
  };
  SolveHooks hooks;
  hooks.progress = &progress;
  hooks.after_step = after_step;
  hooks.load_path_checkpoints = checkpoints;
  hooks.load_path_resume = resume;
  return solve_problem(p, u, hooks);
}

io::Json load_path_newton_check(Problem& p, const std::vector<double>& u, const ProbeHistory& first) {
  TangentModel& model = p.physics();
  ModelHistory* history = model.history();
  const std::optional<HistoryState> saved = history ? std::optional<HistoryState>(history->save_history()) : std::nullopt;
  if (history) history->reset_history();
  LoadPathOptions opt = load_path_options(p.scene.solver);
  opt.diagnose_unstable_state = false;  // (the run's own path was examined: a second factorization adds nothing)
  opt.scheme = LoadPathScheme::newton;
  opt.newton = newton_options(p);  // Newton's own tolerances, the scene's linear solver
  ProbeHistory second;
  std::vector<double> un(model.dofs(), 0.0);
  std::vector<LoadStage> stages = p.stages;
  PathScale u_path, s_path;  // for a path that ends at rest
  const double t0 = wall_seconds();
  const SolveReport rep = solve_load_path(model, stages, opt, un, nullptr,
                                          [&](const LoadStepRecord& r, const std::vector<double>& v) {
                                            second.record(p, r, v);
                                            u_path.add(v);
                                            s_path.add(model.stress_measure(v.data()));
                                          });
  const double seconds = wall_seconds() - t0;
  const std::vector<double> sn = model.stress_measure(un.data());
  if (history) history->restore_history(*saved);
  const std::vector<double> s = model.stress_measure(u.data());
  bool rest_u = false, rest_s = false;
  const Difference du = difference(u, un, nullptr, &u_path, &rest_u), ds = difference(s, sn, nullptr, &s_path, &rest_s);
  // Per probe: max over steps |a - b| over max over steps |b|, for value, von Mises and xi.
  double probes_max = 0.0;
  const std::size_t columns = first.rows.empty() ? 0 : first.rows[0].size();
  for (std::size_t c = kStepColumns; c < columns; ++c) {
    double dmax = 0.0, bmax = 0.0;
    for (std::size_t r = 0; r < std::min(first.rows.size(), second.rows.size()); ++r) {
      dmax = std::max(dmax, std::abs(first.rows[r][c] - second.rows[r][c]));
      bmax = std::max(bmax, std::abs(second.rows[r][c]));
    }
    if (bmax > 0.0) probes_max = std::max(probes_max, dmax / bmax);
  }
  io::Json j = check_json(du, ds, rep, seconds);
  j["probe_histories_relative_max"] = probes_max;
  const bool rest = rest_u || rest_s;
  if (rest) j["relative_to"] = "the largest along the path (the end is at rest)";
  std::printf("perinom: Newton check: displacement differs by %.3e, stress by %.3e (relative L2%s), probe "
              "histories by %.3e (relative max over steps); Newton: %lld iterations, %.3f s\n",
              du.relative_l2, ds.relative_l2,
              rest ? ", over the largest along the path: the path ends at rest, where both are rounding" : "",
              probes_max, static_cast<long long>(rep.iterations), seconds);
  warn_if_apart(du, ds, rep);
  return j;
}

}  // namespace perinom::cli
