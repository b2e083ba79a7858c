#include "perinom/scene/scene_breaking.hpp"

#include <stdexcept>

#include "perinom/geometry/region.hpp"
#include "perinom/models/correspondence.hpp"
#include "perinom/scene/scene.hpp"
#include "scene_loading.hpp"

namespace perinom {

SceneBreaking::SceneBreaking(Problem& p) : p_(&p) {
  const auto& d = p.scene.damage;
  if (!d) throw std::logic_error("SceneBreaking: the scene has no damage section");
  DamageCriterion c = DamageCriterion::instability;
  parse_damage_criterion(d->criterion, c);
  const double parameter = c == DamageCriterion::instability ? d->s_max : c == DamageCriterion::stretch ? d->s_c : d->f_t;
  auto& body = p.as<CorrespondenceModel>();
  if (d->fracture_energy > 0.0) {
    // After the precracks: the family sums are the body's as cut (G_f checked in problem.cpp).
    body.soften_broken_bonds({d->f_t, d->fracture_energy, body.material().E});
  }
  breaking_ = std::make_unique<BondBreaking>(body, p.cloud, c, parameter);
  for (std::size_t k = 0; k < d->no_fail.size(); ++k)
    breaking_->hold(detail::select_region(d->no_fail[k], p.scene, p.cloud, d->no_fail_where[k]));
  BondBreaking* b = breaking_.get();
  // find runs at the u whose force was just taken (ModelChanges): its grad u is kept.
  const CorrespondenceModel* model = &body;
  changes_ = {[b, model](const double* x) { return b->find(x, model->last_gradient()); },
              [b](const double* x, double* f) {
                const BondBreaks made = b->apply(x, f);
                return ChangesMade{made.broken, made.released};
              },
              d->every,
              [b] { return b->stable_time_step(); },
              [b] { return b->state(); },
              [b](const std::vector<double>& s) { b->restore(s); },
              [b]() -> const std::vector<double>& { return b->row_sums(); },
              d->fracture_energy > 0.0,  // softening bonds dissipate between breaks
              [model]() -> const std::vector<ParticleId>& { return model->G().detached(); }};
}

void SceneBreaking::report(SolveReport& r, bool verlet) const {
  r.changes.broken = static_cast<std::int64_t>(breaking_->broken());
  r.changes.detached = static_cast<std::int64_t>(p_->as<CorrespondenceModel>().G().detached().size());
  if (verlet && breaking_->armed_at_find() > 0) r.changes.armed_step = breaking_->armed_at_find() * p_->scene.damage->every;
  r.changes.hourglass_threshold = breaking_->hourglass_threshold();
  if (const CohesiveBonds* soft = p_->as<CorrespondenceModel>().cohesive())
    r.changes.spent = static_cast<std::int64_t>(soft->spent()), r.changes.opening_limit = soft->opening_limit();
}

}  // namespace perinom
