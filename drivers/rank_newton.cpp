#include "rank_newton.hpp"

#include <cstdio>

#include "difference.hpp"
#include "perinom/core/timer.hpp"
#include "perinom/scene/registry.hpp"

namespace perinom::cli {

NewtonOptions rank_newton_options(const SolverSpec& solver, const RankRun& run) {
  NewtonOptions o = newton_options(solver);
  o.memory_limit = run.local.memory_limit;  // --max-memory, a bound for each rank
  const int d = run.local.cloud.dim;
  if (o.linear_solver == "gamg" && run.model.dofs_per_particle() == d) {  // a solid (a plate's w: constants)
    o.dimension = d;
    o.positions.assign(run.local.cloud.x.begin(), run.local.cloud.x.begin() + std::ptrdiff_t(run.part.owned * d));
  }
  return o;
}

io::Json rank_newton_check(const RankRun& run, DistributedModel& model, const Loading& loading,
                           const std::vector<double>& u) {
  std::vector<double> un;
  const double t0 = wall_seconds();
  const SolveReport rep = solve_newton(model, loading, rank_newton_options(run.frame.scene.solver, run), un, nullptr);
  const double seconds = max_over_ranks(wall_seconds() - t0);
  const Difference du = difference(u, un, &model);
  const Difference ds = difference(model.stress_measure(u.data()), model.stress_measure(un.data()), &model);
  std::printf("perinom: Newton check: displacement differs by %.3e, stress by %.3e (relative L2); Newton: %lld "
              "iterations, %.3f s on %d ranks\n",
              du.relative_l2, ds.relative_l2, static_cast<long long>(rep.iterations), seconds, run.ranks);
  warn_if_apart(du, ds, rep);
  return check_json(du, ds, rep, seconds);
}

}  // namespace perinom::cli
