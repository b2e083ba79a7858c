#include "perinom/core/thread_governor.hpp"

#include <omp.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "perinom/core/timer.hpp"

namespace perinom {
namespace {

/// Governors alive on this thread: only the outermost one acts.
thread_local int depth = 0;

/// The last trial's choice and until when it holds: a loop that starts again soon (ADR at
/// every load step of a load path) keeps it instead of paying for a new trial each time.
struct Remembered {
  int threads = 0;
  double until = 0.0;
};
thread_local Remembered remembered;

bool environment_says(const char* value) {
  const char* v = std::getenv("PERINOM_THREAD_GOVERNOR");
  return v && std::strcmp(v, value) == 0;
}

}  // namespace

ThreadGovernor::ThreadGovernor() {
  caller_ = full_ = current_ = omp_get_max_threads();
  active_ = depth == 0 && full_ > 1 && !omp_in_parallel() && !environment_says("off");
  verbose_ = environment_says("verbose");
  ++depth;
  if (!active_) return;
  const double now = wall_seconds();
  if (remembered.threads > 0 && now < remembered.until) {
    begin(Phase::exploit, remembered.threads, now);
    until_ = remembered.until;
  } else {
    begin(Phase::one, 1, now);
  }
}

void ThreadGovernor::forget() { remembered = Remembered{}; }

ThreadGovernor::~ThreadGovernor() {
  --depth;
  if (active_) omp_set_num_threads(caller_);
}

void ThreadGovernor::begin(Phase phase, int threads, double now) {
  phase_ = phase;
  warm_ = false;
  start_ = now;
  iterations_ = 0;
  if (threads == current_) return;
  current_ = threads;
  omp_set_num_threads(threads);
  // Idle pool threads spin before they sleep (libgomp: for milliseconds), on the free core,
  // while the one thread left may share the busy one: release them, so that one thread is
  // one thread (the team is created again at the next switch, once per trial).
  if (threads == 1) omp_pause_resource_all(omp_pause_soft);
}

void ThreadGovernor::tick() {
  if (!active_) return;
  const double now = wall_seconds();
  if (phase_ == Phase::exploit) {
    if (now >= until_) begin(Phase::one, 1, now);
    return;
  }
  if (!warm_) {  // the iteration that paid for the switch ends here
    warm_ = true;
    start_ = now;
    return;
  }
  ++iterations_;
  const double elapsed = now - start_;
  if (iterations_ < trial_iterations || elapsed < trial_seconds) return;
  if (phase_ == Phase::one) {
    one_ = elapsed / iterations_;
    trial_length_ = elapsed;
    begin(Phase::team, full_, now);
    return;
  }
  team_ = elapsed / iterations_;
  trial_length_ += elapsed;
  ++trials_;
  begin(Phase::exploit, team_ < one_ ? full_ : 1, now);
  until_ = now + exploit_factor * trial_length_;
  remembered = {current_, until_};
  if (verbose_)
    std::fprintf(stderr, "thread governor: %.3g ms per iteration on 1 thread, %.3g ms on %d: %d\n", one_ * 1e3,
                 team_ * 1e3, full_, current_);
}

}  // namespace perinom
