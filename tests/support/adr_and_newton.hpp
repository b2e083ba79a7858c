#pragma once
// Test support: the same static problem solved by ADR at a tight tolerance and by Newton,
// and how far apart the answers are (the design's cross-check of the two solvers).
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "perinom/models/loading.hpp"
#include "perinom/models/tangent_model.hpp"
#include "perinom/solvers/adr.hpp"
#include "perinom/solvers/newton.hpp"

namespace perinom::test {

struct AdrAndNewton {
  std::vector<double> adr, newton;
  long newton_iterations = 0;
  double relative_l2 = 0.0;  ///< |u_adr - u_newton| / |u_newton|
};

/// ADR to a relative residual of 1e-11 (increment 1e-13), then Newton with its defaults;
/// both must converge.
inline AdrAndNewton adr_and_newton(TangentModel& model, const Loading& loading) {
  AdrAndNewton r;
  AdrOptions adr;
  adr.tolerance = 1e-11, adr.displacement_tolerance = 1e-13;
  REQUIRE(solve_adr(model, loading, adr, r.adr).converged);
  const SolveReport rep = solve_newton(model, loading, NewtonOptions{}, r.newton);
  INFO(rep.failure);
  REQUIRE(rep.converged);
  r.newton_iterations = rep.iterations;
  double d2 = 0.0, n2 = 0.0;
  for (std::size_t k = 0; k < r.adr.size(); ++k)
    d2 += (r.adr[k] - r.newton[k]) * (r.adr[k] - r.newton[k]), n2 += r.newton[k] * r.newton[k];
  r.relative_l2 = std::sqrt(d2 / n2);
  return r;
}

}  // namespace perinom::test
