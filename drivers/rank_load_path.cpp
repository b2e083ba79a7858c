#include "rank_load_path.hpp"

#include "perinom/scene/registry.hpp"
#include "rank_newton.hpp"

namespace perinom::cli {
namespace {

/// The point probes' row after a load step: each probe's values from the rank that owns its
/// particle, summed over the ranks (the others add zeros).
std::vector<double> probe_row(const RankRun& run, const LoadStepRecord& r, const std::vector<double>& u) {
  std::vector<const BoundProbe*> probes;
  for (const auto& probe : run.frame.probes)
    if (!probe.spec.is_line) probes.push_back(&probe);
  if (probes.empty()) return {};
  const auto owned = owned_index(run.part);
  const ProbeReadout readout(run.local, run.model.local_state(u.data()));
  std::vector<double> values(probes.size() * ProbeHistory::probe_columns, 0.0);
  for (std::size_t k = 0; k < probes.size(); ++k) {
    const auto at = owned.find(probes[k]->particles.at(0));
    if (at == owned.end()) continue;
    BoundProbe mine = *probes[k];
    mine.particles[0] = ParticleId(at->second);
    add_probe_values(readout, mine, values.data() + k * ProbeHistory::probe_columns);
  }
  sum_over_ranks(values.data(), int(values.size()));
  std::vector<double> row = ProbeHistory::step_columns(r);
  row.insert(row.end(), values.begin(), values.end());
  return row;
}

}  // namespace

SolveReport run_rank_load_path(const RankRun& run, DistributedModel& model, std::vector<LoadStage>& stages,
                               const std::string& dir, std::vector<double>& u, io::PvdSeries& series,
                               ProbeHistory& probes, std::int64_t& last_snapshot) {
  const Scene& scene = run.frame.scene;
  LoadPathOptions opt = load_path_options(scene.solver);
  const NewtonOptions newton = rank_newton_options(scene.solver, run);
  opt.newton.positions = newton.positions, opt.newton.dimension = newton.dimension;
  opt.diagnose_unstable_state = false;  // (a serial factorization of the whole tangent: not of a rank's part)
  print_load_path_plan(scene, stages, opt);  // (the other ranks' stdout is silenced)
  std::int64_t done = 0;
  StepProgress progress;
  auto after_step = [&](const LoadStepRecord& r, const std::vector<double>& state) {
    ++done;
    std::vector<double> row = probe_row(run, r, state);
    if (!row.empty()) probes.rows.push_back(std::move(row));
    print_load_step(scene, r);
    progress.step_done();
    if (snapshot_due(scene, done)) {
      add_piece_snapshot(series, double(done), run, state, dir);
      last_snapshot = done;
    }
  };
  return solve_load_path(model, stages, opt, u, &progress, after_step);
}

}  // namespace perinom::cli
