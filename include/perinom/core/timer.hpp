#pragma once
/// @file Wall-clock timing of named phases.
#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace perinom {

/// Records the wall time of consecutive named phases (seconds).
class PhaseTimer {
 public:
  /// Ends the running phase (if any) and starts the phase @p name.
  void start(const std::string& name);
  /// Ends the running phase.
  void stop();
  const std::vector<std::pair<std::string, double>>& phases() const { return phases_; }
  double total() const;

 private:
  using Clock = std::chrono::steady_clock;
  std::vector<std::pair<std::string, double>> phases_;
  std::string running_;
  Clock::time_point since_{};
};

/// Seconds since an arbitrary fixed point (for benchmarks and progress).
double wall_seconds();

}  // namespace perinom
