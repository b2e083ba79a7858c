#pragma once
/// @file The critical stretch from a fracture energy G_c (issue 17): the bond-based (PMB)
/// calibration the peers publish (Silling and Askari 2005 in 3-D, s_c = sqrt(5 G_c / (9 kappa
/// delta)); Ha and Bobaru 2010 in 2-D, s_c = sqrt(4 pi G_c / (9 E delta)) in plane stress),
/// written for any influence function w: the micromodulus c(r) = c0 w(r) is fixed by the bulk
/// modulus (an isotropic stretch s stores the continuum's energy), and G_c is the energy of the
/// bonds that cross a unit area of a plane, each at stretch s_c:
///   3-D: c0 = 9 kappa / (2 pi I3),      G_c = pi c0 s_c^2 I4 / 2   ->  s_c^2 = 4 G_c I3 / (9 kappa I4)
///   2-D: c0 = 4 kappa2 / (pi t I2),     G_c = t c0 s_c^2 I3        ->  s_c^2 = pi G_c I2 / (4 kappa2 I3)
/// with I_n = integral of w(r) r^n over [0, delta], kappa = lambda + 2 mu / 3 and in 2-D the
/// plane law's kappa2 = lambda + mu (plane stress with the reduced lambda), t the thickness.
/// With w = 1 these are the published formulas. A correspondence model stores its energy
/// otherwise; the calibration is the convention, not a property of that model.
#include "perinom/materials/linear_elastic.hpp"
#include "perinom/operators/influence.hpp"

namespace perinom {

struct BondCalibration {
  int dim = 3;
  double bulk = 0.0;       ///< kappa (3-D) or the plane law's kappa2 (2-D), Pa
  Influence weight = Influence::constant;
  double delta = 0.0;      ///< horizon (m)
  double thickness = 1.0;  ///< 2-D only (m)
};

/// The calibration for an elastic material (its dim and plane condition) and horizon.
BondCalibration bond_calibration(const LinearElastic& m, Influence weight, double delta, double thickness);

/// I_n = integral_0^delta w(r) r^n dr (n >= 2).
double influence_moment(Influence weight, double delta, int n);

/// c0 of the micromodulus c(r) = c0 w(r): pair force c s per unit volume squared.
double micromodulus_scale(const BondCalibration& c);

/// s_c for a fracture energy G_c (J/m^2). Throws std::invalid_argument unless G_c > 0.
double critical_stretch(const BondCalibration& c, double G_c);

/// The energy of one pair of unit volumes at stretch s: c0 w(r) s^2 r / 2 (J/m^6).
double pair_energy(const BondCalibration& c, double r, double s);

}  // namespace perinom
