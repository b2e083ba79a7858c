#include "perinom/materials/drucker_prager.hpp"

#include <algorithm>
#include <cmath>

namespace perinom {
namespace {

// Invariants of a compression-positive stress sc: I1, the deviator s and q = sqrt(s:s / 2).
struct Invariants {
  double I1, s[9], q;
};

Invariants invariants(const double* sc) {
  Invariants v;
  v.I1 = sc[0] + sc[4] + sc[8];
  double ss = 0.0;
  for (int k = 0; k < 9; ++k) {
    v.s[k] = sc[k] - (k % 4 == 0 ? v.I1 / 3.0 : 0.0);
    ss += v.s[k] * v.s[k];
  }
  v.q = std::sqrt(0.5 * ss);
  return v;
}

// sigma + C : deps (tension positive).
void elastic_trial(const double* sigma, const double* deps, double K, double G, double* out) {
  const double tr = deps[0] + deps[4] + deps[8], lambda = K - 2.0 * G / 3.0;
  for (int k = 0; k < 9; ++k) out[k] = sigma[k] + 2.0 * G * deps[k] + (k % 4 == 0 ? lambda * tr : 0.0);
}

// eps_p += C^-1 : (trial - sigma): the strain the return took out of the elastic part.
void add_plastic_strain(const double* trial, const double* sigma, double K, double G, double* eps_p) {
  double d[9], tr = 0.0;
  for (int k = 0; k < 9; ++k) d[k] = trial[k] - sigma[k];
  tr = d[0] + d[4] + d[8];
  for (int k = 0; k < 9; ++k) eps_p[k] += (d[k] - (k % 4 == 0 ? tr / 3.0 : 0.0)) / (2.0 * G) + (k % 4 == 0 ? tr / (9.0 * K) : 0.0);
}

// The elastic trial from state n and its compression-positive invariants.
struct Trial {
  double sigma[9];
  Invariants v;
};

Trial trial_state(const DruckerPrager& dp, const DruckerPrager::State& n, const double* deps) {
  Trial t;
  elastic_trial(n.sigma, deps, dp.bulk(), dp.shear(), t.sigma);
  double sc[9];
  for (int k = 0; k < 9; ++k) sc[k] = -t.sigma[k];
  t.v = invariants(sc);
  return t;
}

// The radial return at multiplier dl: xi = xi_n + dl/2, q = q_tr - G dl,
// I1 = I1_tr + 9 K m d0 A dl; f there, and df/d dl (dm = dm/d dl).
struct RadialPoint {
  double m, dm, I1, f, slope;
};

RadialPoint radial_point(const DruckerPrager& dp, const Invariants& v, double xi_n, double dl) {
  const double K = dp.bulk(), G = dp.shear(), a = dp.A(), b = dp.B(), d0 = dp.d0;
  RadialPoint p;
  p.m = dp.m(xi_n + 0.5 * dl);
  p.dm = 0.5 * dp.m_prime(xi_n + 0.5 * dl);
  p.I1 = v.I1 + 9.0 * K * p.m * d0 * a * dl;
  p.f = v.q - G * dl - p.m * (a * p.I1 + b);
  p.slope = -G - p.dm * (a * p.I1 + b) - p.m * a * 9.0 * K * d0 * a * (p.m + dl * p.dm);
  return p;
}

}  // namespace

double DruckerPrager::A() const {
  const double s = std::sin(friction_angle);
  return 2.0 * s / (std::sqrt(3.0) * (3.0 - s));
}

double DruckerPrager::B() const {
  const double s = std::sin(friction_angle);
  return 6.0 * cohesion * std::cos(friction_angle) / (std::sqrt(3.0) * (3.0 - s));
}

double DruckerPrager::yield(const double* sigma, double xi) const {
  double sc[9];
  for (int k = 0; k < 9; ++k) sc[k] = -sigma[k];
  const Invariants v = invariants(sc);
  return v.q - m(xi) * (A() * v.I1 + B());
}

void DruckerPrager::elastic(const State& n, const double* deps, State& out) const {
  out = n;
  elastic_trial(n.sigma, deps, bulk(), shear(), out.sigma);
}

DruckerPrager::Return DruckerPrager::update(const State& n, const double* deps, State& out) const {
  const double K = bulk(), G = shear(), a = A(), b = B();
  const Trial t = trial_state(*this, n, deps);
  const Invariants& v = t.v;
  const double* trial = t.sigma;
  out = n;
  std::copy(trial, trial + 9, out.sigma);
  const double f_trial = v.q - m(n.xi) * (a * v.I1 + b);
  const double scale = std::max({v.q, std::abs(a * v.I1) + b, 1e-300});
  if (f_trial <= 1e-12 * scale) return Return::elastic;

  const double upper = v.q / G;
  if (a > 0.0 && radial_point(*this, v, n.xi, upper).f >= 0.0) {
    // Apex: s = 0 and A I1 + B = 0; the deviatoric plastic strain is s_tr / 2G.
    for (int k = 0; k < 9; ++k) out.sigma[k] = k % 4 == 0 ? b / (3.0 * a) : 0.0;  // I1 = -B/A
    out.xi = n.xi + 0.5 * upper;
    add_plastic_strain(trial, out.sigma, K, G, out.eps_p);
    return Return::apex;
  }
  // f decreases on [0, upper] from f_trial > 0 to below 0: Newton, kept inside the bracket.
  double lo = 0.0, hi = upper, dl = std::min(upper, f_trial / (G + 9.0 * K * m(n.xi) * m(n.xi) * d0 * a * a));
  for (int it = 0; it < 100; ++it) {
    const RadialPoint p = radial_point(*this, v, n.xi, dl);
    const double r = p.f, slope = p.slope;
    if (std::abs(r) <= 1e-14 * scale) break;
    (r > 0.0 ? lo : hi) = dl;
    double next = slope < 0.0 ? dl - r / slope : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (hi - lo <= 1e-16 * upper) break;
    dl = next;
  }
  const double I1 = radial_point(*this, v, n.xi, dl).I1, shrink = 1.0 - G * dl / v.q;
  for (int k = 0; k < 9; ++k) out.sigma[k] = -(v.s[k] * shrink + (k % 4 == 0 ? I1 / 3.0 : 0.0));
  out.xi = n.xi + 0.5 * dl;
  add_plastic_strain(trial, out.sigma, K, G, out.eps_p);
  return Return::smooth;
}

DruckerPrager::Return DruckerPrager::tangent(const State& n, const double* deps, State& out, double* D) const {
  const Return r = update(n, deps, out);
  const double K = bulk(), G = shear(), lambda = K - 2.0 * G / 3.0;
  auto id = [](int a, int b) { return a == b ? 1.0 : 0.0; };
  if (r == Return::apex) {
    std::fill(D, D + 81, 0.0);
    return r;
  }
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      for (int c = 0; c < 3; ++c)
        for (int e = 0; e < 3; ++e) D[((a * 3 + b) * 3 + c) * 3 + e] = 2.0 * G * id(a, c) * id(b, e) + lambda * id(a, b) * id(c, e);
  if (r == Return::elastic) return r;
  // Smooth return, compression positive (the signs cancel in d sigma / d eps). With
  // nhat = s_tr / 2 q_tr: d q_tr = 2G nhat : de, d I1_tr = 3K tr de, and F(dl; q_tr, I1_tr) = 0
  // gives d dl = (2G nhat - 3K m A I) : de / (-dF/d dl).
  const Invariants v = trial_state(*this, n, deps).v;
  const double a_ = A(), dl = 2.0 * (out.xi - n.xi);
  const RadialPoint p = radial_point(*this, v, n.xi, dl);
  const double mm = p.m, dm = p.dm, slope = p.slope;
  double ddl[9], dq[9];
  for (int k = 0; k < 9; ++k) {
    dq[k] = 2.0 * G * v.s[k] / (2.0 * v.q);
    ddl[k] = (dq[k] - (k % 4 == 0 ? 3.0 * K * mm * a_ : 0.0)) / -slope;
  }
  // s = s_tr (1 - G dl / q_tr): ds = (1 - G dl/q) ds_tr + s_tr (G dl dq / q^2 - G d dl / q);
  // I1 = I1_tr + 9 K m d0 A dl: dI1 = 3K tr de + 9 K d0 A (m + dl dm) d dl.
  const double shrink = 1.0 - G * dl / v.q, grow = 9.0 * K * d0 * a_ * (mm + dl * dm);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      for (int c = 0; c < 3; ++c)
        for (int e = 0; e < 3; ++e) {
          const int ce = c * 3 + e;
          const double ds_tr = 2.0 * G * (id(a, c) * id(b, e) - id(a, b) * id(c, e) / 3.0);
          double d = shrink * ds_tr + v.s[a * 3 + b] * (G * dl * dq[ce] / (v.q * v.q) - G * ddl[ce] / v.q);
          d += id(a, b) * (K * id(c, e) + grow * ddl[ce] / 3.0);
          D[((a * 3 + b) * 3 + c) * 3 + e] = d;
        }
  return r;
}

void DruckerPrager::update_substepped(const State& n, const double* deps, int substeps, State& out) const {
  const double K = bulk(), G = shear(), a = A(), b = B();
  double d[9], trial[9];
  for (int k = 0; k < 9; ++k) d[k] = deps[k] / substeps;
  out = n;
  for (int step = 0; step < substeps; ++step) {
    elastic_trial(out.sigma, d, K, G, trial);
    double sc[9];
    for (int k = 0; k < 9; ++k) sc[k] = -out.sigma[k];
    const Invariants v = invariants(sc);
    double dl = 0.0;
    if (yield(trial, out.xi) > 0.0 && v.q > 0.0) {
      // Continuum operator at the start of the sub-step: dl = (n_f : C : de) / (n_f : C : n_g + H),
      // n_f = s/2q - m A I, n_g = s/2q - m d0 A I, H = m'(xi) (A I1 + B) / 2 (compression positive).
      const double mm = m(out.xi), dm = m_prime(out.xi);
      double s_de = 0.0;
      const double tr_de = -(d[0] + d[4] + d[8]);
      for (int k = 0; k < 9; ++k) s_de += v.s[k] * -d[k];
      const double num = G * s_de / v.q - 3.0 * K * mm * a * tr_de;
      const double den = G + 9.0 * K * mm * mm * d0 * a * a + 0.5 * dm * (a * v.I1 + b);
      dl = std::max(0.0, num / den);
      // sigma_c += C : de_c - dl (G s / q - 3 K m d0 A I); in tension-positive terms:
      for (int k = 0; k < 9; ++k)
        trial[k] += dl * (G * v.s[k] / v.q - (k % 4 == 0 ? 3.0 * K * mm * d0 * a : 0.0));
      for (int k = 0; k < 9; ++k)
        out.eps_p[k] -= dl * (v.s[k] / (2.0 * v.q) - (k % 4 == 0 ? mm * d0 * a : 0.0));
    }
    std::copy(trial, trial + 9, out.sigma);
    out.xi += 0.5 * dl;
  }
}

}  // namespace perinom
