#pragma once
/// @file A solver loop's thread count, chosen by timing the loop itself.

namespace perinom {

/// Chooses, for the iterations of one loop, between the full OpenMP team and a single thread,
/// whichever runs an iteration faster now. On a machine where another process holds a core,
/// a team whose threads meet at barriers several times per iteration waits for the thread that
/// shares its core with that process, and runs slower than one thread alone (the demo at
/// dx = 0.5 mm with one of two cores busy: 1.5 times slower; see docs/performance.md).
///
/// Every `period` iterations the governor times `window` iterations on one thread and
/// `window` on the full team (the first iteration after each switch is not timed), compares
/// the medians and keeps the faster count until the next trial. Results do not depend on the
/// choice: the library's sums are independent of the thread count (core/parallel.hpp).
///
/// Inert when the team has one thread, inside another governor's loop (the outer loop
/// governs), or when the environment variable PERINOM_THREAD_GOVERNOR is "off" (benchmarks
/// that measure a fixed team). The destructor restores the caller's thread count.
class ThreadGovernor {
 public:
  static constexpr int window = 8;
  static constexpr int period = 400;

  ThreadGovernor();
  ~ThreadGovernor();
  ThreadGovernor(const ThreadGovernor&) = delete;
  ThreadGovernor& operator=(const ThreadGovernor&) = delete;

  /// Call once at the start of every iteration of the loop.
  void tick();
  /// The thread count of the iterations since the last tick.
  int threads() const { return current_; }

 private:
  void use(int threads);

  bool active_ = false;
  int caller_ = 1, full_ = 1, current_ = 1;
  int k_ = 0;
  double last_ = 0.0;
  double one_[window] = {}, team_[window] = {};
};

}  // namespace perinom
