#pragma once
/// @file A solver loop's thread count, chosen by timing the loop itself.

namespace perinom {

/// Chooses, for the iterations of one loop, between the full OpenMP team and a single thread,
/// whichever runs the loop faster now. On a machine where another process holds a core, a
/// team whose threads meet at barriers several times per iteration waits for the thread that
/// shares its core with that process, and runs slower than one thread alone (the demo at
/// dx = 0.5 mm with one of two cores busy: 1.5 to 1.8 times slower; docs/performance.md).
///
/// The loop alternates a trial and a stretch of exploitation: the trial times the loop on one
/// thread, then on the team, each for at least `trial_iterations` iterations and
/// `trial_seconds` (the first iteration after a switch is not timed: it pays for the switch);
/// the faster count then runs for `exploit_factor` times the trial's length, and the next
/// trial begins. The choice outlives the governor until then: a loop started again within that
/// time (ADR at each load step of a load path) keeps it without a new trial. Short trials mislead: the scheduler favours a thread that has just woken, so a
/// team looks fast under load for a few milliseconds. Results do not depend on the choice: the
/// library's sums are independent of the thread count (core/parallel.hpp).
///
/// Inert when the team has one thread, inside another governor's loop (the outer loop
/// governs), or when the environment variable PERINOM_THREAD_GOVERNOR is "off" (benchmarks
/// that measure a fixed team); "verbose" prints each trial's figures and choice to stderr.
/// The destructor restores the caller's thread count.
class ThreadGovernor {
 public:
  static constexpr int trial_iterations = 8;
  static constexpr double trial_seconds = 0.05;
  static constexpr double exploit_factor = 10.0;

  ThreadGovernor();
  ~ThreadGovernor();
  ThreadGovernor(const ThreadGovernor&) = delete;
  ThreadGovernor& operator=(const ThreadGovernor&) = delete;

  /// Call once at the start of every iteration of the loop.
  void tick();
  /// The thread count of the iterations since the last tick.
  int threads() const { return current_; }
  /// How many trials have ended (with a choice).
  int trials() const { return trials_; }
  /// False when inert (one thread, an outer governor, or PERINOM_THREAD_GOVERNOR=off).
  bool active() const { return active_; }
  /// Drops the remembered choice: the next governor starts with a trial.
  static void forget();

 private:
  enum class Phase { one, team, exploit };
  void begin(Phase phase, int threads, double now);

  bool active_ = false, verbose_ = false;
  int caller_ = 1, full_ = 1, current_ = 1, trials_ = 0;
  Phase phase_ = Phase::one;
  bool warm_ = false;       ///< the phase's untimed first iteration is over
  double start_ = 0.0;      ///< when the phase's timed iterations began (s)
  long iterations_ = 0;     ///< timed iterations of the phase
  double one_ = 0.0, team_ = 0.0, trial_length_ = 0.0;  ///< s per iteration; s
  double until_ = 0.0;  ///< when the exploitation ends (s, wall_seconds)
};

}  // namespace perinom
