#pragma once
/// @file What a loading on a local part needs of the ranks (issue 19): its face-located
/// constraints read and react on ghost dofs.
#include <memory>
#include <vector>

#include "perinom/distributed/ranks.hpp"
#include "perinom/models/loading.hpp"
#include "perinom/neighbors/local_part.hpp"

namespace perinom {

/// The LoadingRanks (loading.hpp) of `part` with `dofs_per_particle` dofs a particle: one
/// array over the part's dofs filled from the owners, one whose ghosts are added to them.
class LoadingShare : public LoadingRanks {
 public:
  LoadingShare(const LocalPart& part, int dofs_per_particle);
  std::size_t owned_dofs() const override { return owned_dofs_; }
  const double* with_ghosts(const double* u) const override;
  double* zeroed_scratch() const override;
  void add_ghosts_to_owners() const override { scratch_halo_->add_to_owners(); }
  double max(double v) const override { return max_over_ranks(v); }

 private:
  std::size_t owned_dofs_;
  mutable std::vector<double> values_, scratch_;  // the halos' arrays: they must not move
  std::unique_ptr<Halo> values_halo_, scratch_halo_;
};

}  // namespace perinom
