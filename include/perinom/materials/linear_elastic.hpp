#pragma once
/// @file Isotropic linear elasticity, small strain (THEORY sec. 3). Knows nothing of particles.
#include <string>

namespace perinom {

enum class PlaneCondition { none, strain, stress };

/// sigma = lambda tr(eps) I + 2 mu eps with eps = sym(H), H = grad u (d x d, row-major).
/// In 2-D, plane strain keeps lambda; plane stress uses lambda* = 2 lambda mu / (lambda + 2 mu).
struct LinearElastic {
  double E = 0.0;        ///< Young's modulus (Pa)
  double nu = 0.0;       ///< Poisson's ratio
  double density = 0.0;  ///< kg/m^3
  int dim = 3;
  PlaneCondition plane = PlaneCondition::none;

  double mu() const { return E / (2.0 * (1.0 + nu)); }
  /// The Lame constant used in the d x d law (plane stress: the reduced one).
  double lambda() const;

  /// P (d x d) = sigma(sym H). Small strain: the first Piola-Kirchhoff stress is sigma.
  void stress(const double* H, double* P) const;
  /// psi = 1/2 sigma : eps (J/m^3).
  double energy(const double* H) const;
  /// dP_ab / dH_ce as d^4 values, C[((a*d + b)*d + c)*d + e].
  void tangent(double* C) const;
  /// The full 3 x 3 Cauchy stress (row-major): in plane strain sigma_zz = lambda tr(eps),
  /// in plane stress 0.
  void stress3(const double* H, double* sigma) const;
};

/// Throws InputError, naming the field, unless E > 0, -1 < nu < 0.5, density > 0 (all finite)
/// and dim is 2 or 3: other constants give NaN or a stiffness of the wrong sign.
void check_material(const LinearElastic& m);

/// von Mises equivalent stress of a 3 x 3 stress (Pa).
double von_mises(const double* sigma3);

}  // namespace perinom
