#include "perinom/models/plastic_points.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace perinom {

PlasticPoints::PlasticPoints(const DruckerPrager& law, int dim, std::size_t particles)
    : law_(law), dim_(dim), committed_(particles), trial_(particles), flagged_(particles, 0) {}

void PlasticPoints::increment(const Point& n, const double* H, Point& out, double* deps) const {
  strain(H, out.eps);
  for (int k = 0; k < 9; ++k) deps[k] = out.eps[k] - n.eps[k];
}

void PlasticPoints::cauchy(const Point& point, double* sigma) const {
  std::copy(point.law.sigma, point.law.sigma + 9, sigma);
}

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
  Point out;
  double deps[9];
  increment(committed_[i], H, out, deps);
  law_.update(committed_[i].law, deps, out.law);
  return out;
}

void PlasticPoints::advance(std::size_t i, const double* deps, Point& t) const {
  if (mode_ == PlasticMode::lbc && !flagged_[i])
    law_.elastic(committed_[i].law, deps, t.law);
  else
    law_.update(committed_[i].law, deps, t.law);
}

void PlasticPoints::stress(std::size_t i, const double* H, double* P) {
  Point& t = trial_[i];
  double deps[9];
  increment(committed_[i], H, t, deps);
  advance(i, deps, t);
  in_plane(t.law.sigma, P);
}

void PlasticPoints::tangent(std::size_t i, const double* H, double* C) const {
  const Point& n = committed_[i];
  double eps[9], deps[9], sigma[9], D[81];
  strain(H, eps);
  for (int k = 0; k < 9; ++k) deps[k] = eps[k] - n.eps[k];
  tangent(i, deps, sigma, D);
  // eps = sym(H): dP_ab/dH_ce = (D_abce + D_abec) / 2, in-plane components only.
  const int d = dim_;
  for (int a = 0; a < d; ++a)
    for (int b = 0; b < d; ++b)
      for (int c = 0; c < d; ++c)
        for (int e = 0; e < d; ++e)
          C[((a * d + b) * d + c) * d + e] =
              0.5 * (D[((a * 3 + b) * 3 + c) * 3 + e] + D[((a * 3 + b) * 3 + e) * 3 + c]);
}

void PlasticPoints::update(std::size_t i, const double* deps, double* sigma) {
  Point& t = trial_[i];
  for (int k = 0; k < 9; ++k) t.eps[k] = committed_[i].eps[k] + deps[k];
  advance(i, deps, t);
  std::copy(t.law.sigma, t.law.sigma + 9, sigma);
}

void PlasticPoints::evaluate(std::size_t i, const double* deps, double* sigma) const {
  DruckerPrager::State out;
  law_.update(committed_[i].law, deps, out);
  std::copy(out.sigma, out.sigma + 9, sigma);
}

void PlasticPoints::tangent(std::size_t i, const double* deps, double* sigma, double* D) const {
  DruckerPrager::State out;
  law_.tangent(committed_[i].law, deps, out, D);
  std::copy(out.sigma, out.sigma + 9, sigma);
}

double PlasticPoints::stored_energy(std::size_t i) const {
  // 1/2 sigma : C^-1 sigma, the elastic strain taken from the (unrotated) stress.
  const double* s = trial_[i].law.sigma;
  const double K = law_.bulk(), G = law_.shear(), p = (s[0] + s[4] + s[8]) / 3.0;
  double ss = 0.0;
  for (int k = 0; k < 9; ++k) {
    const double dev = s[k] - (k % 4 == 0 ? p : 0.0);
    ss += dev * dev;
  }
  return ss / (4.0 * G) + 9.0 * p * p / (2.0 * 9.0 * K);
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

std::vector<LawField> PlasticPoints::fields() const {
  std::vector<LawField> out{{"stress", 9}};
  for (auto& f : state_fields()) out.push_back(std::move(f));
  return out;
}

void PlasticPoints::field(const std::string& name, const double* H, std::vector<double>& values) const {
  if (name != "stress") return state_field(name, values);
  values.resize(size() * 9);
  cauchy(H, values.data());
}

std::vector<LawField> PlasticPoints::state_fields() const {
  return {{"eq_plastic_strain", 1}, {"plastic_strain", 9}, {"yielded", 1}, {"lbc_flagged", 1}};
}

void PlasticPoints::state_field(const std::string& name, std::vector<double>& values) const {
  const std::size_t n = size();
  if (name == "eq_plastic_strain" || name == "yielded") {
    values.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const double xi = committed_[i].law.xi;
      values[i] = name == "yielded" ? (xi > 0.0 ? 1.0 : 0.0) : xi;
    }
  } else if (name == "plastic_strain") {
    values.resize(n * 9);
    for (std::size_t i = 0; i < n; ++i) std::copy(committed_[i].law.eps_p, committed_[i].law.eps_p + 9, values.begin() + i * 9);
  } else if (name == "lbc_flagged") {
    values.assign(flagged_.begin(), flagged_.end());
  } else {
    throw std::invalid_argument("PlasticPoints: no output field '" + name +
                                "' (it offers: stress, eq_plastic_strain, plastic_strain, yielded, lbc_flagged)");
  }
}

void PlasticPoints::reset() {
  const Point virgin;
  std::fill(committed_.begin(), committed_.end(), virgin);
  std::fill(trial_.begin(), trial_.end(), virgin);
  std::fill(flagged_.begin(), flagged_.end(), std::uint8_t{0});
}

void PlasticPoints::restore(std::vector<Point> committed, std::vector<std::uint8_t> flags) {
  if (committed.size() != size() || flags.size() != size())
    throw std::invalid_argument("PlasticPoints::restore: " + std::to_string(committed.size()) + " states and " +
                                std::to_string(flags.size()) + " flags for " + std::to_string(size()) + " particles");
  committed_ = std::move(committed);
  trial_ = committed_;
  flagged_ = std::move(flags);
}

std::size_t PlasticPoints::flagged() const {
  return static_cast<std::size_t>(std::count(flagged_.begin(), flagged_.end(), std::uint8_t{1}));
}

std::size_t PlasticPoints::memory_bytes() const {
  return (committed_.size() + trial_.size()) * sizeof(Point) + flagged_.size();
}

}  // namespace perinom
