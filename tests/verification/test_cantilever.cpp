// The slender bodies of the formulation issue: cantilevers in bending, where the seed's
// improved formulation converged to a tip deflection of the wrong sign (every particle lies
// in its band E). The default (consistent) formulation against converged CalculiX references
// (verification/fem/cantilever_2d.py, cantilever_3d.py); the targets are 3% at 8 and
// 1% at 16 particles through the thickness (docs/verification/formulation.md has the sweep).
#include <catch2/catch.hpp>

#include "perinom/scene/problem.hpp"
#include "perinom/solvers/newton.hpp"

using namespace perinom;

namespace {

double tip(const char* scene, const std::vector<std::string>& sets) {
  Problem p = build_problem(read_scene(std::string(PERINOM_SOURCE_DIR "/verification/formulation/") + scene, sets));
  std::vector<double> u;
  REQUIRE(solve_newton(p.as<CorrespondenceModel>(), p.loading, NewtonOptions{}, u).converged);
  std::vector<double> sigma, H(u.size() * p.cloud.dim);
  p.as<CorrespondenceModel>().stress3(u.data(), sigma);
  p.as<CorrespondenceModel>().gradient(u.data(), H.data());
  return point_probe_value(p.probes.at(0), {p.cloud, u, sigma, H});
}

}  // namespace

TEST_CASE("the plane-stress cantilever bends the right way, within 3% at 8 particles through the thickness", "[verification][consistent]") {
  const double fem = -2.012016e-4;
  const double uy = tip("cantilever_2d.yaml", {"discretization.dx=0.00125"});
  WARN("2-D cantilever, 8 through the thickness: tip u_y = " << uy << " m, FEM " << fem << ", error "
       << (uy / fem - 1) * 100 << "% (measured +2.3%)");
  CHECK(std::abs(uy / fem - 1.0) <= 0.03);
}

TEST_CASE("the 3-D cantilever 4 particles thick bends the right way (the improved formulation did not)", "[verification][consistent]") {
  // At 4 particles through the thickness the issue found +2.9e-6 m with improved (wrong sign)
  // and -3.56e-4 m with classical (78% soft); consistent gives -2.081e-4 (+3.9%).
  const double fem = -2.0020e-4;
  const double uz = tip("cantilever_3d.yaml", {});
  WARN("3-D cantilever, 4 through the thickness: tip u_z = " << uz << " m, FEM " << fem << ", error "
       << (uz / fem - 1) * 100 << "%");
  CHECK(uz < 0.0);
  CHECK(std::abs(uz / fem - 1.0) <= 0.05);
}
