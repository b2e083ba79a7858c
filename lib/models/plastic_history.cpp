// The Drucker-Prager points' history as a load path drives it (LawHistory): the mode, the
// committed equivalent plastic strain and secant stiffness, and the committed states as
// numbers for checkpoints.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "perinom/models/plastic_points.hpp"

namespace perinom {

void PlasticPoints::set_history_mode(HistoryMode mode) {
  set_mode(mode == HistoryMode::flagged ? PlasticMode::lbc : PlasticMode::return_map);
}

std::vector<double> PlasticPoints::history_variable() const {
  std::vector<double> xi;
  xi.reserve(committed_.size());
  for (const auto& point : committed_) xi.push_back(point.law.xi);
  return xi;
}

std::vector<double> PlasticPoints::secant_ratios() const {
  std::vector<double> ratio(committed_.size(), 1.0);
  const double two_g = 2.0 * law_.shear();
  for (std::size_t i = 0; i < committed_.size(); ++i) {
    const Point& p = committed_[i];
    const double mean_s = (p.law.sigma[0] + p.law.sigma[4] + p.law.sigma[8]) / 3.0;
    const double mean_e = (p.eps[0] + p.eps[4] + p.eps[8]) / 3.0;
    double s2 = 0.0, e2 = 0.0;
    for (int k = 0; k < 9; ++k) {
      const double on_diagonal = k % 4 == 0 ? 1.0 : 0.0;
      const double s = p.law.sigma[k] - on_diagonal * mean_s, e = p.eps[k] - on_diagonal * mean_e;
      s2 += s * s, e2 += e * e;
    }
    if (e2 > 0.0) ratio[i] = std::min(1.0, std::sqrt(s2 / e2) / two_g);
  }
  return ratio;
}

HistoryState PlasticPoints::save_history() const {
  HistoryState s;
  s.values.reserve(committed_.size() * values_per_particle());
  for (const auto& point : committed_) {
    s.values.insert(s.values.end(), point.law.sigma, point.law.sigma + 9);
    s.values.insert(s.values.end(), point.law.eps_p, point.law.eps_p + 9);
    s.values.push_back(point.law.xi);
    s.values.insert(s.values.end(), point.eps, point.eps + 9);
  }
  s.flags = flagged_;
  return s;
}

void PlasticPoints::restore_history(const HistoryState& s) {
  const std::size_t m = values_per_particle();
  if (s.values.size() != s.flags.size() * m)
    throw std::invalid_argument("PlasticPoints: the history holds " + std::to_string(s.values.size()) +
                                " values for " + std::to_string(s.flags.size()) + " flags (" + std::to_string(m) +
                                " per particle)");
  std::vector<Point> points(s.flags.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double* x = s.values.data() + i * m;
    std::copy(x, x + 9, points[i].law.sigma), std::copy(x + 9, x + 18, points[i].law.eps_p);
    points[i].law.xi = x[18];
    std::copy(x + 19, x + 28, points[i].eps);
  }
  restore(std::move(points), s.flags);
}

}  // namespace perinom
