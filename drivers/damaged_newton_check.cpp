#include "damaged_newton_check.hpp"

#include <algorithm>
#include <cstdio>

#include "perinom/core/timer.hpp"
#include "perinom/models/correspondence.hpp"
#include "perinom/scene/registry.hpp"
#include "difference.hpp"

namespace perinom::cli {
namespace {

/// Holds these dofs at zero in `l` (those it does not constrain already); a face-located
/// loading gets them as constraints without couplings.
void hold_at_zero(Loading& l, const std::vector<std::int64_t>& dofs) {
  const bool coupled = !l.couplings.empty();
  for (const std::int64_t dof : dofs) {
    if (std::find(l.fixed.begin(), l.fixed.end(), dof) != l.fixed.end()) continue;
    l.fix(dof, 0.0);
    if (coupled) l.couplings.push_back(l.couplings.back()), l.scale.push_back(1.0);
  }
  if (coupled) l.index_couplings();
}

}  // namespace

io::Json damaged_newton_check(Problem& p, const std::vector<double>& u) {
  TangentModel& model = p.physics();
  const int d = model.dofs_per_particle();
  const auto& detached = p.as<CorrespondenceModel>().G().detached();
  std::vector<std::int64_t> held;
  for (const ParticleId i : detached)
    for (int a = 0; a < d; ++a) held.push_back(static_cast<std::int64_t>(i) * d + a);
  // The broken model is linear elastic (the scene refuses damage with drucker_prager and
  // solver.check newton): its equilibrium at the final loads does not depend on the path,
  // so one Newton step per stage reaches it.
  std::vector<LoadStage> stages = p.stages;
  for (LoadStage& st : stages) {
    st.steps = 1;
    hold_at_zero(st.loading, held);
  }
  LoadPathOptions opt = load_path_options(p.scene.solver);
  opt.scheme = LoadPathScheme::newton;
  opt.newton = newton_options(p);
  std::vector<double> un(model.dofs(), 0.0);
  const double t0 = wall_seconds();
  const SolveReport rep = solve_load_path(model, stages, opt, un);
  const double seconds = wall_seconds() - t0;
  // A detached particle carries nothing and moves as it was left: not part of the answer.
  std::vector<double> ua = u;
  for (const std::int64_t k : held) ua[k] = un[k] = 0.0;
  const std::vector<double> s = model.stress_measure(ua.data()), sn = model.stress_measure(un.data());
  const Difference du = difference(ua, un), ds = difference(s, sn);
  io::Json j = check_json(du, ds, rep, seconds);
  j["at"] = "final damage state";
  j["detached_held"] = static_cast<long long>(detached.size());
  std::printf("perinom: Newton check at the final damage state (%zu bonds broken, %zu detached particles held): "
              "displacement differs by %.3e, stress by %.3e (relative L2); Newton: %lld iterations, %.3f s%s%s\n",
              p.as<CorrespondenceModel>().G().graph().broken(), detached.size(), du.relative_l2, ds.relative_l2,
              static_cast<long long>(rep.iterations), seconds, rep.failure.empty() ? "" : "; ",
              rep.failure.c_str());
  return j;
}

}  // namespace perinom::cli
