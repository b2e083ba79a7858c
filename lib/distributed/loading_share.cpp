#include "perinom/distributed/loading_share.hpp"

#include <algorithm>

namespace perinom {

LoadingShare::LoadingShare(const LocalPart& part, int dofs_per_particle)
    : owned_dofs_(part.owned * std::size_t(dofs_per_particle)),
      values_(part.particles.size() * std::size_t(dofs_per_particle), 0.0),
      scratch_(values_.size(), 0.0) {
  const std::vector<std::int64_t> ghosts(part.global.begin() + std::ptrdiff_t(part.owned), part.global.end());
  values_halo_ = std::make_unique<Halo>(part.owned, ghosts, dofs_per_particle, values_.data());
  scratch_halo_ = std::make_unique<Halo>(part.owned, ghosts, dofs_per_particle, scratch_.data());
}

const double* LoadingShare::with_ghosts(const double* u) const {
  std::copy(u, u + owned_dofs_, values_.begin());
  values_halo_->update();
  return values_.data();
}

double* LoadingShare::zeroed_scratch() const {
  std::fill(scratch_.begin(), scratch_.end(), 0.0);
  return scratch_.data();
}

}  // namespace perinom
