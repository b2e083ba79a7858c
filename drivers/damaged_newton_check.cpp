#include "damaged_newton_check.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>

#include "perinom/core/timer.hpp"
#include "perinom/models/correspondence.hpp"
#include "perinom/scene/registry.hpp"
#include "difference.hpp"

namespace perinom::cli {
namespace {

/// Holds these dofs of `l` where `u` has them at the stage's end (those it does not constrain
/// already): at u itself in the first stage, where nothing was before it, and where the stage
/// starts in the later ones (Loading::begin_stage). A face-located loading gets them as
/// constraints without couplings.
void hold(Loading& l, const std::vector<std::int64_t>& dofs, const std::vector<double>& u, bool first) {
  const bool coupled = !l.couplings.empty();
  for (const std::int64_t dof : dofs) {
    if (std::find(l.fixed.begin(), l.fixed.end(), dof) != l.fixed.end()) continue;
    l.fix(dof, first ? u[dof] : 0.0);
    if (coupled) l.couplings.push_back(l.couplings.back()), l.scale.push_back(1.0);
  }
  if (coupled) l.index_couplings();
}

}  // namespace

io::Json damaged_newton_check(Problem& p, const std::vector<double>& u, const PathScale& stress_path) {
  TangentModel& model = p.physics();
  const int d = model.dofs_per_particle();
  const auto& detached = p.as<CorrespondenceModel>().G().detached();
  std::vector<std::int64_t> held;
  for (const ParticleId i : detached)
    for (int a = 0; a < d; ++a) held.push_back(static_cast<std::int64_t>(i) * d + a);
  // The broken model is linear elastic (the scene refuses damage with drucker_prager and
  // solver.check newton): its equilibrium at the final loads does not depend on the path,
  // so one Newton step per stage reaches it. Softening bonds keep the largest openings the
  // path committed; below them each is a secant spring, convex, so the path's balanced state
  // (every opening at or below its kappa) is the one equilibrium of that secant body, and
  // Newton from zero finds it unless an iterate takes a bond onto its softening branch.
  std::vector<LoadStage> stages = p.stages;
  for (std::size_t k = 0; k < stages.size(); ++k) {
    stages[k].steps = 1;
    hold(stages[k].loading, held, u, k == 0);
  }
  LoadPathOptions opt = load_path_options(p.scene.solver);
  opt.diagnose_unstable_state = false;  // (the run's own path was examined: a second factorization adds nothing)
  opt.scheme = LoadPathScheme::newton;
  opt.newton = newton_options(p);
  std::vector<double> un(model.dofs(), 0.0);
  const double t0 = wall_seconds();
  const SolveReport rep = solve_load_path(model, stages, opt, un);
  const double seconds = wall_seconds() - t0;
  // A detached particle carries nothing, but its live bonds still enter its neighbours'
  // gradients: Newton holds it where the path left it.
  const std::vector<double> s = model.stress_measure(u.data()), sn = model.stress_measure(un.data());
  bool rest = false;
  const Difference du = difference(u, un), ds = difference(s, sn, nullptr, &stress_path, &rest);
  io::Json j = check_json(du, ds, rep, seconds);
  j["at"] = "final damage state";
  if (rest) j["stress_relative_to"] = "the largest along the path (the broken body ends unstressed)";
  j["detached_held"] = static_cast<long long>(detached.size());
  std::printf("perinom: Newton check at the final damage state (%zu bonds broken, %zu detached particles held where the path left them): "
              "displacement differs by %.3e, stress by %.3e (relative L2%s); Newton: %lld iterations, %.3f s%s%s\n",
              p.as<CorrespondenceModel>().G().graph().broken(), detached.size(), du.relative_l2, ds.relative_l2,
              rest ? ", stress over the largest along the path: the broken body ends unstressed, where both are rounding" : "",
              static_cast<long long>(rep.iterations), seconds, rep.failure.empty() ? "" : "; ",
              rep.failure.c_str());
  warn_if_apart(du, ds, rep);
  return j;
}

}  // namespace perinom::cli
