#include "perinom/scene/scene_breaking.hpp"

#include <stdexcept>

#include "perinom/geometry/region.hpp"
#include "perinom/models/correspondence.hpp"
#include "perinom/scene/scene.hpp"

namespace perinom {

SceneBreaking::SceneBreaking(Problem& p) : p_(&p) {
  const auto& d = p.scene.damage;
  if (!d) throw std::logic_error("SceneBreaking: the scene has no damage section");
  DamageCriterion c = DamageCriterion::instability;
  parse_damage_criterion(d->criterion, c);
  const double parameter = c == DamageCriterion::instability ? d->s_max : c == DamageCriterion::stretch ? d->s_c : d->f_t;
  breaking_ = std::make_unique<BondBreaking>(p.as<CorrespondenceModel>(), p.cloud, c, parameter);
  for (const Region& zone : d->no_fail) breaking_->hold(select(zone, p.scene.geometry, p.cloud));
  BondBreaking* b = breaking_.get();
  // find runs at the u whose force was just taken (ModelChanges): its grad u is kept.
  const CorrespondenceModel* model = &p.as<CorrespondenceModel>();
  changes_ = {[b, model](const double* x) { return b->find(x, model->last_gradient()); },
              [b](const double* x, double* f) {
                const BondBreaks made = b->apply(x, f);
                return ChangesMade{made.broken, made.released};
              },
              d->every,
              [b] { return b->stable_time_step(); },
              [b] { return b->state(); },
              [b](const std::vector<double>& s) { b->restore(s); },
              [b]() -> const std::vector<double>& { return b->row_sums(); }};
}

void SceneBreaking::report(SolveReport& r, bool verlet) const {
  r.changes.broken = static_cast<std::int64_t>(breaking_->broken());
  r.changes.detached = static_cast<std::int64_t>(p_->as<CorrespondenceModel>().G().detached().size());
  if (verlet && breaking_->armed_at_find() > 0) r.changes.armed_step = breaking_->armed_at_find() * p_->scene.damage->every;
  r.changes.hourglass_threshold = breaking_->hourglass_threshold();
}

}  // namespace perinom
