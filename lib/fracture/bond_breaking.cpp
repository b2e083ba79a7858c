#include "perinom/fracture/bond_breaking.hpp"

#include <stdexcept>

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

std::size_t BondBreaking::find(const double* u) {
  const BondGraph& g = model_->G().graph();
  switch (criterion_) {
    case DamageCriterion::instability:
      bond_stretches(*cloud_, g, u, measure_);
      H_.resize(cloud_->size() * cloud_->dim * cloud_->dim);
      model_->gradient(u, H_.data());
      hourglass_strains(*cloud_, g, u, H_.data(), hourglass_);
      due_ = instability_->select(g, measure_, hourglass_);
      break;
    case DamageCriterion::stretch:
      bond_stretches(*cloud_, g, u, measure_);
      due_ = bonds_above(g, measure_, parameter_);
      break;
    case DamageCriterion::stress:
      model_->stress3(u, sigma_);
      sigma1_.resize(cloud_->size());
      for (std::size_t i = 0; i < sigma1_.size(); ++i) sigma1_[i] = max_principal_stress(sigma_.data() + i * 9);
      bond_stresses(g, sigma1_, measure_);
      due_ = bonds_above(g, measure_, parameter_);
      break;
  }
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
