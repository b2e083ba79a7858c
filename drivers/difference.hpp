#pragma once
// How far apart two answers to the same problem are (the Newton checks of `perinom run`), and
// what the checks report.
#include <algorithm>
#include <cmath>
#include <vector>

#include "perinom/io/json_writer.hpp"
#include "perinom/solvers/adr.hpp"

namespace perinom::cli {

struct Difference {
  double relative_l2 = 0.0;   ///< |a - b| / |b|
  double relative_max = 0.0;  ///< max |a - b| / max |b|
};

/// a against the reference b (same length); plain norms where b is zero.
inline Difference difference(const std::vector<double>& a, const std::vector<double>& b) {
  double d2 = 0, b2 = 0, dmax = 0, bmax = 0;
  for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k) {
    d2 += (a[k] - b[k]) * (a[k] - b[k]), b2 += b[k] * b[k];
    dmax = std::max(dmax, std::abs(a[k] - b[k])), bmax = std::max(bmax, std::abs(b[k]));
  }
  return {b2 > 0 ? std::sqrt(d2 / b2) : std::sqrt(d2), bmax > 0 ? dmax / bmax : dmax};
}

/// What every Newton check writes into summary.json `check`: the two differences (of u and of
/// the model's stress measure, ADR's answer against Newton's) and how Newton went.
inline io::Json check_json(const Difference& du, const Difference& ds, const SolveReport& newton, double seconds) {
  io::Json j = io::Json::object();
  j["displacement_relative_l2"] = du.relative_l2;
  j["displacement_relative_max"] = du.relative_max;
  j["stress_relative_l2"] = ds.relative_l2;
  j["stress_relative_max"] = ds.relative_max;
  j["newton_iterations"] = static_cast<long long>(newton.iterations);
  j["newton_converged"] = newton.converged;
  j["newton_residual"] = newton.residual;
  j["newton_seconds"] = seconds;
  if (!newton.failure.empty()) j["newton_error"] = newton.failure;
  return j;
}

}  // namespace perinom::cli
