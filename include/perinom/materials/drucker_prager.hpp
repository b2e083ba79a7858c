#pragma once
/// @file Drucker-Prager elastoplasticity with hyperbolic hardening (THEORY sec. 9), small
/// strain, integrated by the closest point projection. Knows nothing of particles.
///
/// The interface takes and returns tension-positive 3 x 3 tensors (row-major), like
/// LinearElastic::stress3. Inside, as in THEORY sec. 9 and the seed, compression is
/// positive: I1 = tr(-sigma), s = dev(-sigma), q = sqrt(J2) = sqrt(s:s / 2).
///   f = q - m(xi) (A I1 + B),   g = q - m(xi) d0 A I1,   m(xi) = (m0 + h xi) / (1 + h xi),
///   A = 2 sin(phi) / (sqrt(3) (3 - sin(phi))),   B = 6 c cos(phi) / (sqrt(3) (3 - sin(phi))).
/// The reading of the seed's illegible equations 38, 39 and 46 is THEORY's (docs/theory.md).

namespace perinom {

struct DruckerPrager {
  double E = 0.0;               ///< Young's modulus (Pa)
  double nu = 0.0;              ///< Poisson's ratio
  double friction_angle = 0.0;  ///< phi (radians)
  double cohesion = 0.0;        ///< c (Pa)
  double m0 = 1.0;              ///< initial hardening factor, 0 < m0 <= 1
  double d0 = 0.0;              ///< dilatancy: 0 none, 1 associated flow
  double h = 0.0;               ///< hardening rate; 0: m = m0 throughout

  /// The committed state of one material point.
  struct State {
    double sigma[9] = {};  ///< Cauchy stress, tension positive
    double eps_p[9] = {};  ///< plastic strain, tension positive
    double xi = 0.0;       ///< equivalent plastic strain (THEORY sec. 9)
  };
  enum class Return { elastic, smooth, apex };

  double bulk() const { return E / (3.0 * (1.0 - 2.0 * nu)); }
  double shear() const { return E / (2.0 * (1.0 + nu)); }
  double A() const;
  double B() const;
  double m(double xi) const { return (m0 + h * xi) / (1.0 + h * xi); }
  /// dm/dxi.
  double m_prime(double xi) const { return h * (1.0 - m0) / ((1.0 + h * xi) * (1.0 + h * xi)); }
  /// f at a tension-positive stress and xi (Pa; > 0 outside the yield surface).
  double yield(const double* sigma, double xi) const;

  /// Backward-Euler update from the committed state `n` by the total strain increment
  /// `deps` (3 x 3, tension positive): the elastic trial, then, when f > 0, the closest
  /// point projection in invariant space (one scalar equation for the plastic multiplier,
  /// the seed's cubic once m is cleared, solved by safeguarded Newton) or the apex return.
  Return update(const State& n, const double* deps, State& out) const;
  /// The elastic trial alone: sigma = sigma_n + C : deps, plastic variables kept.
  void elastic(const State& n, const double* deps, State& out) const;

  /// The consistent (algorithmic) tangent of `update`: D[((a*3 + b)*3 + c)*3 + e] =
  /// d sigma_ab / d deps_ce of the same increment (C when elastic, 0 at the apex), and the
  /// updated state in `out`. Not symmetric when d0 != 1 (non-associated flow).
  Return tangent(const State& n, const double* deps, State& out, double* D) const;

  /// The reference the return map is checked against: the rate equations integrated
  /// explicitly in `substeps` equal sub-increments (continuum elastoplastic operator,
  /// first order), without any return to the surface.
  void update_substepped(const State& n, const double* deps, int substeps, State& out) const;
};

}  // namespace perinom
