// The critical stretch from G_c (fracture/critical_stretch.hpp): the published closed forms
// with a constant influence function, and the check PDMATLAB2D makes on a discretization: the
// energy of the bonds crossing a plane, each at s_c, per unit area is G_c (within 5%).
#include <catch2/catch.hpp>

#include <cmath>

#include "../support/clouds.hpp"
#include "perinom/fracture/critical_stretch.hpp"
#include "perinom/fracture/precrack.hpp"
#include "perinom/neighbors/search.hpp"

using namespace perinom;

namespace {

LinearElastic steel(int dim, PlaneCondition plane) {
  LinearElastic m;
  m.E = 210e9, m.nu = dim == 2 && plane == PlaneCondition::stress ? 1.0 / 3.0 : 0.25, m.density = 7800.0;
  m.dim = dim, m.plane = plane;
  return m;
}

/// The energy of the pairs crossing the crack window, each at stretch s, per unit area of it
/// (2-D: window length times the thickness 1 of the unit lattice).
double energy_across(const PointCloud& c, const Families& f, const Precrack& window, const BondCalibration& cal,
                     double s) {
  double sum = 0.0;
  for (const auto& [i, j] : bonds_crossing(c, f, {window})) {
    double r2 = 0.0;
    for (int a = 0; a < c.dim; ++a) r2 += std::pow(c.x[j * c.dim + a] - c.x[i * c.dim + a], 2);
    sum += pair_energy(cal, std::sqrt(r2), s) * c.volume[i] * c.volume[j];
  }
  const auto& e1 = window.edge1;
  const auto& e2 = window.edge2;
  const double area = c.dim == 2 ? std::hypot(e1[0], e1[1]) : std::hypot(e1[0], e1[1], e1[2]) * std::hypot(e2[0], e2[1], e2[2]);
  return sum / area;
}

}  // namespace

TEST_CASE("s_c from G_c is the published formula with a constant influence function", "[fracture]") {
  const double G = 22170.0, delta = 3e-3;
  const LinearElastic m3 = steel(3, PlaneCondition::none);
  const double kappa = m3.E / (3.0 * (1.0 - 2.0 * m3.nu));
  // Silling and Askari (2005): s_c = sqrt(5 G_c / (9 kappa delta)).
  CHECK(critical_stretch(bond_calibration(m3, Influence::constant, delta, 1.0), G) ==
        Approx(std::sqrt(5.0 * G / (9.0 * kappa * delta))).epsilon(1e-12));
  // Ha and Bobaru (2010), plane stress (nu = 1/3): s_c = sqrt(4 pi G_c / (9 E delta)); the
  // thickness cancels.
  const LinearElastic m2 = steel(2, PlaneCondition::stress);
  CHECK(critical_stretch(bond_calibration(m2, Influence::constant, delta, 0.01), G) ==
        Approx(std::sqrt(4.0 * M_PI * G / (9.0 * m2.E * delta))).epsilon(1e-12));
  // The micromodulus of their papers: c = 18 kappa / (pi delta^4), 9 E / (pi t delta^3).
  CHECK(micromodulus_scale(bond_calibration(m3, Influence::constant, delta, 1.0)) ==
        Approx(18.0 * kappa / (M_PI * std::pow(delta, 4))).epsilon(1e-12));
  CHECK(micromodulus_scale(bond_calibration(m2, Influence::constant, delta, 0.01)) ==
        Approx(9.0 * m2.E / (M_PI * 0.01 * std::pow(delta, 3))).epsilon(1e-12));
  CHECK_THROWS_AS(critical_stretch(bond_calibration(m3, Influence::constant, delta, 1.0), 0.0), std::invalid_argument);
}

TEST_CASE("the Gaussian influence moments match their closed form", "[fracture]") {
  // integral_0^delta exp(-4 r^2 / delta^2) r^3 dr = delta^4 (1 - 5 e^-4) / 32
  const double delta = 2.5;
  CHECK(influence_moment(Influence::gaussian, delta, 3) ==
        Approx(std::pow(delta, 4) * (1.0 - 5.0 * std::exp(-4.0)) / 32.0).epsilon(1e-10));
  CHECK(influence_moment(Influence::inverse_square, delta, 2) == Approx(std::pow(delta, 3)).epsilon(1e-14));
}

TEST_CASE("the bonds across a plane, each at s_c, hold G_c per unit area (2-D and 3-D)", "[fracture]") {
  // Full volumes within the horizon, no partial-volume correction: the sum converges with
  // m = delta / dx, from the lattice's shells. In 2-D m = 3 is within 5%; in 3-D m = 3 misses
  // by 15% (constant w) and 6% (inverse square), m = 5 is within 3% (docs/scene-format.md).
  const double G = 1000.0;
  const PointCloud c2 = test::lattice(2, 40, 0.0);
  const Families f2 = radius_families(c2, 3.015);
  const PointCloud c3 = test::lattice(3, 24, 0.0);
  const Families f3 = radius_families(c3, 5.015);
  // Planes between particle rows (the lattice's particles sit at k + 1/2), windows away from
  // the free sides by more than a horizon.
  Precrack w2, w3;
  w2.origin = {20.0, 10.0, 0.0};
  w2.edge1 = {0.0, 20.0, 0.0};
  w3.origin = {12.0, 7.0, 7.0};
  w3.edge1 = {0.0, 10.0, 0.0};
  w3.edge2 = {0.0, 0.0, 10.0};
  for (Influence w : {Influence::constant, Influence::inverse_distance, Influence::inverse_square, Influence::gaussian}) {
    INFO("influence " << int(w));
    const BondCalibration cal2 = bond_calibration(steel(2, PlaneCondition::strain), w, 3.015, 1.0);
    CHECK(energy_across(c2, f2, w2, cal2, critical_stretch(cal2, G)) == Approx(G).epsilon(0.05));
    const BondCalibration cal3 = bond_calibration(steel(3, PlaneCondition::none), w, 5.015, 1.0);
    CHECK(energy_across(c3, f3, w3, cal3, critical_stretch(cal3, G)) == Approx(G).epsilon(0.05));
  }
}
