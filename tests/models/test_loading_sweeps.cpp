// Face-located constraints are solved by sweeps: they must meet E u = t exactly when the
// sweeps contract, and stop with a SolveError naming a constraint when they do not (they
// once stopped silently after 200 sweeps, leaving E u != t in a run that exited 0).
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "perinom/core/error.hpp"
#include "perinom/models/loading.hpp"

using namespace perinom;

namespace {

// Two constraints on dofs 0 and 1 of a face, each reading the other with weight w and the
// free dof 2 with weight 0.25: u0 + w u1 + 0.25 u2 = t0 and u1 + w u0 + 0.25 u2 = t1.
Loading two_on_a_face(double w) {
  Loading l;
  const int wall = l.add_support("wall");
  l.fix(0, 1.0, wall);
  l.fix(1, -2.0, wall);
  l.couplings = {0, 2, 4};
  l.coupled = {1, 2, 0, 2};
  l.coef = {w, 0.25, w, 0.25};
  l.scale = {1.0, 1.0};
  l.index_couplings();
  return l;
}

double row(const Loading& l, std::size_t k, const double* u) {
  double sum = u[l.fixed[k]] / l.scale[k];
  for (Offset c = l.couplings[k]; c < l.couplings[k + 1]; ++c) sum += l.coef[c] * u[l.coupled[c]];
  return sum;
}

}  // namespace

TEST_CASE("impose meets the face constraints to rounding when the sweeps contract", "[loading]") {
  const Loading l = two_on_a_face(0.6);  // Gauss-Seidel contracts (factor 0.36 a sweep)
  double u[3] = {0.0, 0.0, 0.8};
  l.impose(1.0, u);
  CHECK(row(l, 0, u) == Approx(1.0).margin(1e-14));
  CHECK(row(l, 1, u) == Approx(-2.0).margin(1e-14));
  // The multipliers solve (E_FF)^T lambda = -r_F: r = (1, 1, 0) gives lambda0 + 0.6 lambda1 = -1.
  double fint[3] = {-1.0, -1.0, 0.0}, lambda[2];
  l.multipliers(fint, 1.0, lambda);
  CHECK(lambda[0] + 0.6 * lambda[1] == Approx(-1.0).margin(1e-14));
  CHECK(lambda[1] + 0.6 * lambda[0] == Approx(-1.0).margin(1e-14));
}

TEST_CASE("impose and the multipliers stop with a SolveError naming the support when the sweeps diverge", "[loading]") {
  const Loading l = two_on_a_face(1.5);  // each sweep multiplies the error by 2.25
  double u[3] = {0.0, 0.0, 0.8};
  try {
    l.impose(1.0, u);
    FAIL("impose returned with E u != t");
  } catch (const SolveError& e) {
    const std::string what = e.what();
    CHECK(what.find("did not converge") != std::string::npos);
    CHECK(what.find("support 'wall'") != std::string::npos);
    CHECK(what.find("dof ") != std::string::npos);
    CHECK(what.find("(at: layer)") != std::string::npos);  // a value the scene reader takes
  }
  double fint[3] = {-1.0, -1.0, 0.0}, lambda[2];
  CHECK_THROWS_AS(l.multipliers(fint, 1.0, lambda), SolveError);
  double r[3] = {1.0, 1.0, 0.0};
  CHECK_THROWS_AS(l.reduce(r), SolveError);
}

TEST_CASE("a NaN state is left to the solver's guard, not reported as a constraint failure", "[loading]") {
  const Loading l = two_on_a_face(0.6);
  double u[3] = {0.0, 0.0, std::nan("")};
  CHECK_NOTHROW(l.impose(1.0, u));
  CHECK(std::isnan(u[0]));
}
