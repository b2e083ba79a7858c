#include "perinom/fracture/bond_breaking.hpp"

#include <algorithm>
#include <stdexcept>

#include "bond_selection.hpp"
#include "perinom/fracture/bond_measures.hpp"
#include "perinom/materials/measures.hpp"

namespace perinom {

bool parse_damage_criterion(const std::string& name, DamageCriterion& c) {
  if (name == "instability") c = DamageCriterion::instability;
  else if (name == "stretch") c = DamageCriterion::stretch;
  else if (name == "stress") c = DamageCriterion::stress;
  else return false;
  return true;
}

BondBreaking::BondBreaking(CorrespondenceModel& model, const PointCloud& cloud, DamageCriterion criterion,
                           double parameter)
    : model_(&model), cloud_(&cloud), criterion_(criterion), parameter_(parameter) {
  if (!(parameter > 0.0)) throw std::invalid_argument("BondBreaking: the criterion's parameter must be positive");
  if (criterion == DamageCriterion::instability) instability_.emplace(parameter);
}

void BondBreaking::hold(const std::vector<ParticleId>& particles) {
  held_.resize(cloud_->size(), 0);
  for (const ParticleId i : particles) held_.at(i) = 1;
}

std::size_t BondBreaking::find(const double* u) {
  using detail::live_bonds_above;
  using detail::live_maximum;
  const BondGraph& g = model_->G().graph();
  const int d = cloud_->dim;
  const BondStretch stretch{d, cloud_->x.data(), u};
  due_.clear();
  switch (criterion_) {
    case DamageCriterion::instability: {
      // One pass a step: the largest stretch until armed (and at that step the largest
      // hourglass strain, once; none exceeds it then), afterwards the hourglass strains.
      auto hourglass = [&] {
        H_.resize(cloud_->size() * d * d);
        model_->gradient(u, H_.data());
        return HourglassStrain{d, cloud_->x.data(), u, H_.data()};
      };
      if (!instability_->armed()) {
        instability_->arm(live_maximum(g, stretch), [&] { return live_maximum(g, hourglass()); });
        break;
      }
      due_ = live_bonds_above(g, instability_->threshold(), hourglass());
      break;
    }
    case DamageCriterion::stretch:
      due_ = live_bonds_above(g, parameter_, stretch);
      break;
    case DamageCriterion::stress: {
      model_->stress3(u, sigma_);
      sigma1_.resize(cloud_->size());
      for (std::size_t i = 0; i < sigma1_.size(); ++i) sigma1_[i] = max_principal_stress(sigma_.data() + i * 9);
      const double* s1 = sigma1_.data();
      due_ = live_bonds_above(g, parameter_, [s1](std::size_t i, std::size_t j) { return 0.5 * (s1[i] + s1[j]); });
      break;
    }
  }
  if (!held_.empty())
    due_.erase(std::remove_if(due_.begin(), due_.end(), [&](const BondPair& b) { return held_[b.first] || held_[b.second]; }),
               due_.end());
  return due_.size();
}

std::size_t BondBreaking::apply() {
  if (due_.empty()) return 0;
  const BondBreaks b = model_->break_bonds(due_);
  due_.clear();
  broken_ += b.broken;
  detached_ = b.detached.size();
  return b.broken;
}

}  // namespace perinom
