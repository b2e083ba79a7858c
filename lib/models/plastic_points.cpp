#include "perinom/models/plastic_points.hpp"

#include <algorithm>
#include <cmath>

namespace perinom {

PlasticPoints::PlasticPoints(const DruckerPrager& law, int dim, std::size_t particles)
    : law_(law), dim_(dim), committed_(particles), trial_(particles), flagged_(particles, 0) {}

void PlasticPoints::strain(const double* H, double* eps) const {
  const int d = dim_;
  std::fill(eps, eps + 9, 0.0);
  for (int a = 0; a < d; ++a)
    for (int b = 0; b < d; ++b) eps[a * 3 + b] = 0.5 * (H[a * d + b] + H[b * d + a]);
}

void PlasticPoints::in_plane(const double* t3, double* t) const {
  for (int a = 0; a < dim_; ++a)
    for (int b = 0; b < dim_; ++b) t[a * dim_ + b] = t3[a * 3 + b];
}

PlasticPoints::Point PlasticPoints::evaluate(std::size_t i, const double* H) const {
  const Point& n = committed_[i];
  Point out;
  strain(H, out.eps);
  double deps[9];
  for (int k = 0; k < 9; ++k) deps[k] = out.eps[k] - n.eps[k];
  law_.update(n.law, deps, out.law);
  return out;
}

void PlasticPoints::stress(std::size_t i, const double* H, double* P) {
  Point& t = trial_[i];
  if (mode_ == PlasticMode::lbc && !flagged_[i]) {
    const Point& n = committed_[i];
    strain(H, t.eps);
    double deps[9];
    for (int k = 0; k < 9; ++k) deps[k] = t.eps[k] - n.eps[k];
    law_.elastic(n.law, deps, t.law);
  } else {
    t = evaluate(i, H);
  }
  in_plane(t.law.sigma, P);
}

void PlasticPoints::tangent(std::size_t i, const double* H, double* C) const {
  const Point& n = committed_[i];
  double eps[9], deps[9], D[81];
  strain(H, eps);
  for (int k = 0; k < 9; ++k) deps[k] = eps[k] - n.eps[k];
  DruckerPrager::State out;
  law_.tangent(n.law, deps, out, D);
  // eps = sym(H): dP_ab/dH_ce = (D_abce + D_abec) / 2, in-plane components only.
  const int d = dim_;
  for (int a = 0; a < d; ++a)
    for (int b = 0; b < d; ++b)
      for (int c = 0; c < d; ++c)
        for (int e = 0; e < d; ++e)
          C[((a * d + b) * d + c) * d + e] =
              0.5 * (D[((a * 3 + b) * 3 + c) * 3 + e] + D[((a * 3 + b) * 3 + e) * 3 + c]);
}

double PlasticPoints::stored_energy(std::size_t i) const {
  const Point& t = trial_[i];
  double w = 0.0;
  for (int k = 0; k < 9; ++k) w += 0.5 * t.law.sigma[k] * (t.eps[k] - t.law.eps_p[k]);
  return w;
}

std::size_t PlasticPoints::flag_violations(double tolerance) {
  std::size_t count = 0;
  const double a = law_.A(), b = law_.B();
  for (std::size_t i = 0; i < trial_.size(); ++i) {
    if (flagged_[i]) continue;
    const auto& s = trial_[i].law;
    const double I1 = -(s.sigma[0] + s.sigma[4] + s.sigma[8]);
    const double strength = law_.m(committed_[i].law.xi) * (a * I1 + b);
    const double f = law_.yield(s.sigma, committed_[i].law.xi);
    if (f > tolerance * std::max(std::abs(strength), law_.m0 * b)) {
      flagged_[i] = 1;
      ++count;
    }
  }
  return count;
}

void PlasticPoints::commit() { committed_ = trial_; }

void PlasticPoints::reset() {
  std::fill(committed_.begin(), committed_.end(), Point{});
  std::fill(trial_.begin(), trial_.end(), Point{});
  std::fill(flagged_.begin(), flagged_.end(), std::uint8_t{0});
}

std::size_t PlasticPoints::flagged() const {
  return static_cast<std::size_t>(std::count(flagged_.begin(), flagged_.end(), std::uint8_t{1}));
}

std::size_t PlasticPoints::memory_bytes() const {
  return (committed_.size() + trial_.size()) * sizeof(Point) + flagged_.size();
}

}  // namespace perinom
