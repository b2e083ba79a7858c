#include "perinom/core/thread_governor.hpp"

#include <omp.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>

#include "perinom/core/timer.hpp"

namespace perinom {
namespace {

/// Governors alive on this thread: only the outermost one acts.
thread_local int depth = 0;

double median(double* t, int n) {
  std::nth_element(t, t + n / 2, t + n);
  return t[n / 2];
}

bool disabled_by_environment() {
  const char* v = std::getenv("PERINOM_THREAD_GOVERNOR");
  return v && std::strcmp(v, "off") == 0;
}

}  // namespace

ThreadGovernor::ThreadGovernor() {
  caller_ = full_ = current_ = omp_get_max_threads();
  active_ = depth == 0 && full_ > 1 && !omp_in_parallel() && !disabled_by_environment();
  ++depth;
  if (!active_) return;
  use(1);
  last_ = wall_seconds();
}

ThreadGovernor::~ThreadGovernor() {
  --depth;
  if (active_) omp_set_num_threads(caller_);
}

void ThreadGovernor::use(int threads) {
  current_ = threads;
  omp_set_num_threads(threads);
}

void ThreadGovernor::tick() {
  if (!active_) return;
  const double now = wall_seconds(), dt = now - last_;
  last_ = now;
  ++k_;
  // Iterations 1..window+1 run on one thread, window+2..2 window+2 on the team; the first of
  // each trial is not timed (it pays for the switch).
  if (k_ <= window + 1) {
    if (k_ >= 2) one_[k_ - 2] = dt;
    if (k_ == window + 1) use(full_);
  } else if (k_ <= 2 * window + 2) {
    if (k_ >= window + 3) team_[k_ - window - 3] = dt;
    if (k_ == 2 * window + 2) use(median(team_, window) < median(one_, window) ? full_ : 1);
  } else if (k_ >= period) {
    k_ = 0;
    use(1);
  }
}

}  // namespace perinom
