#pragma once
// How far apart two answers to the same problem are (the Newton checks of `perinom run`), and
// what the checks report.
#include <algorithm>
#include <cmath>
#include <vector>

#include "perinom/io/json_writer.hpp"
#include "perinom/models/model.hpp"
#include "perinom/solvers/adr.hpp"
#include "diagnostics.hpp"

namespace perinom::cli {

struct Difference {
  double relative_l2 = 0.0;   ///< |a - b| / |b|
  double relative_max = 0.0;  ///< max |a - b| / max |b|
};

/// The largest norms of a field along a load path's steps (one process's values).
struct PathScale {
  double l2 = 0.0, max = 0.0;
  void add(const std::vector<double>& b) {
    double sum = 0.0;
    for (const double v : b) sum += v * v, max = std::max(max, std::abs(v));
    l2 = std::max(l2, std::sqrt(sum));
  }
};

/// An end state whose norm is below this fraction of the largest along its path is at rest
/// (a path unloaded to zero): its own norm is rounding, and a difference is taken over the
/// path's largest instead.
inline constexpr double kUnloadedEnd = 1e-6;

/// a against the reference b (same length); plain norms where b is zero. Over MPI ranks
/// (`ranks` the rank's model, a and b its own values) the norms are the whole body's. With a
/// `path` (serial) whose largest norm b's is below kUnloadedEnd of, over the path's norms
/// (`over_path` then true).
inline Difference difference(const std::vector<double>& a, const std::vector<double>& b, const Model* ranks = nullptr,
                             const PathScale* path = nullptr, bool* over_path = nullptr) {
  double sum[2] = {0, 0}, max[2] = {0, 0};  // |a - b|^2, |b|^2; max |a - b|, max |b|
  for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k) {
    sum[0] += (a[k] - b[k]) * (a[k] - b[k]), sum[1] += b[k] * b[k];
    max[0] = std::max(max[0], std::abs(a[k] - b[k])), max[1] = std::max(max[1], std::abs(b[k]));
  }
  if (ranks) ranks->sum_across_ranks(sum, 2), ranks->max_across_ranks(max, 2);
  const bool rest = path && std::sqrt(sum[1]) < kUnloadedEnd * path->l2;
  if (over_path) *over_path = rest;
  if (rest) sum[1] = path->l2 * path->l2, max[1] = path->max;
  return {sum[1] > 0 ? std::sqrt(sum[0] / sum[1]) : std::sqrt(sum[0]), max[1] > 0 ? max[0] / max[1] : max[0]};
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

/// Two answers further apart than this (relative L2 of displacement or stress) are not one
/// answer: solver tolerances move a converged answer by far less (the examples' checks read
/// 1e-10 to 1e-5).
inline constexpr double kChecksApart = 1e-2;

/// Warns, after a check's own line, when Newton converged to an answer kChecksApart or more
/// from the run's: the number alone was printed for a 2-D cantilever 15% off (ADR stopped by a
/// loose tolerance), with nothing to say it mattered.
inline void warn_if_apart(const Difference& du, const Difference& ds, const SolveReport& newton) {
  if (!newton.converged || !(du.relative_l2 >= kChecksApart || ds.relative_l2 >= kChecksApart)) return;
  warn("solver.check: newton: the run's answer and Newton's differ by %.3g%% in displacement and %.3g%% in "
       "stress (relative L2), more than %g%%: one of them is not the discrete problem's answer (a loose "
       "solver.tolerance or displacement_tolerance stops ADR early: the 2-D cantilever of "
       "verification/formulation/cantilever_2d.yaml is 15%% off at 1e-3), or the problem has more than one (past a "
       "peak of the load or at a bifurcation, where the path decides which); trust neither until they agree",
       100.0 * du.relative_l2, 100.0 * ds.relative_l2, 100.0 * kChecksApart);
}

}  // namespace perinom::cli
