#include "perinom/fracture/bond_breaking.hpp"

#include <algorithm>
#include <cmath>
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

std::size_t BondBreaking::find(const double* u, const double* H) {
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
        if (!H) {
          H_.resize(cloud_->size() * d * d);
          model_->gradient(u, H_.data());
        }
        return HourglassStrain{d, cloud_->x.data(), u, H ? H : H_.data()};
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

double BondBreaking::stable_time_step() {
  if (row_sums_.empty()) {
    row_sums_ = model_->stiffness_row_sums();
    mass_ = model_->lumped_mass();
  }
  double w2 = 0.0;
  for (std::size_t k = 0; k < row_sums_.size(); ++k) w2 = std::max(w2, row_sums_[k] / mass_[k]);
  return 2.0 / std::sqrt(w2);
}

std::size_t BondBreaking::apply() {
  if (due_.empty()) return 0;
  const BondBreaks b = model_->break_bonds(due_);
  due_.clear();
  if (!row_sums_.empty()) {
    // A refreshed row m of G and S changes the stiffness rows of m and of its family.
    const BondGraph& g = model_->G().graph();
    std::vector<ParticleId> rows = b.rows;
    for (const ParticleId m : b.rows)
      for (Offset k = g.begin(m); k < g.end(m); ++k) rows.push_back(g.col(k));
    std::sort(rows.begin(), rows.end());
    rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
    const std::vector<double> sums = model_->stiffness_row_sums(rows);
    const int d = cloud_->dim;
    for (std::size_t r = 0; r < rows.size(); ++r)
      for (int a = 0; a < d; ++a) row_sums_[rows[r] * d + a] = sums[r * d + a];
  }
  broken_ += b.broken;
  detached_ = b.detached.size();
  return b.broken;
}

}  // namespace perinom
