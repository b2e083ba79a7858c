#include "perinom/operators/singular_family.hpp"

#include <sstream>

namespace perinom {
namespace {

std::string rest_of(int d, const double* x, ParticleId i, long family, int order) {
  std::ostringstream msg;
  msg << " at (";
  for (int a = 0; a < d; ++a) msg << (a ? ", " : "") << x[i * d + a];
  if (order == 1) {
    msg << "): shape tensor is singular; its family of " << family << " neighbours does not span R^" << d
        << " (increase discretization.horizon.ratio or discretization.horizon.neighbors)";
  } else {
    msg << "): the second-order K is singular; its family of " << family
        << " neighbours does not determine a quadratic in R^" << d << " (that takes at least "
        << d + d * (d + 1) / 2
        << " neighbours, not all on one conic or quadric: e.g. three distinct layers along each "
           "axis; increase discretization.horizon.ratio or discretization.horizon.neighbors)";
  }
  return msg.str();
}

}  // namespace

SingularFamily::SingularFamily(int dim, const double* x, ParticleId i, long family, int order)
    : InputError("particle " + std::to_string(i) + rest_of(dim, x, i, family, order)),
      particle(i),
      rest_(rest_of(dim, x, i, family, order)) {}

std::string SingularFamily::with_index(ParticleId renumbered) const {
  return "particle " + std::to_string(renumbered) + rest_;
}

}  // namespace perinom
