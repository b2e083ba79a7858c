#pragma once
/// @file A particle whose family cannot carry the nonlocal fit: its shape tensor (first
/// order) or its K (second order) is singular. The error keeps the particle's index, so a
/// caller that built the operator on part of a cloud (an MPI rank's) can name it in the
/// whole cloud's numbering.
#include <string>

#include "perinom/core/error.hpp"
#include "perinom/core/types.hpp"

namespace perinom {

class SingularFamily : public InputError {
 public:
  /// "particle I at (X): REASON", REASON from the family's size and the fit's order (1, 2).
  SingularFamily(int dim, const double* x, ParticleId particle, long family, int order);
  /// The same message with particle `renumbered` (the position stays).
  std::string with_index(ParticleId renumbered) const;
  ParticleId particle;

 private:
  std::string rest_;  // " at (X): REASON"
};

}  // namespace perinom
