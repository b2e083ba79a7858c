// The thread governor (core/thread_governor.hpp): it keeps the faster of one thread and the
// team for a loop, restores the caller's thread count, and stays out of the way when nested
// or switched off. The loop bodies here sleep longer on one count than on the other, three
// times longer, so the decision does not hang on this machine's timing noise.
#include <catch2/catch.hpp>
#include <omp.h>

#include <chrono>
#include <cstdlib>
#include <thread>

#include "perinom/core/thread_governor.hpp"

using namespace perinom;

namespace {

/// Runs a governed loop through its first trial, each iteration sleeping `on_one` ms on one
/// thread and `on_team` ms on more; returns the count the governor kept.
int kept_after_trial(int on_one, int on_team) {
  ThreadGovernor::forget();
  ThreadGovernor governor;
  while (governor.trials() == 0) {
    governor.tick();
    const int ms = omp_get_max_threads() == 1 ? on_one : on_team;
    std::this_thread::sleep_for(std::chrono::milliseconds(ms));
  }
  return governor.threads();
}

struct Team {
  int before = omp_get_max_threads();
  explicit Team(int n) { omp_set_num_threads(n); }
  ~Team() { omp_set_num_threads(before); }
};

}  // namespace

TEST_CASE("the thread governor keeps whichever of one thread and the team runs faster", "[core]") {
  const Team team(2);
  CHECK(kept_after_trial(1, 3) == 1);  // the team is slower: a busy core
  CHECK(kept_after_trial(3, 1) == 2);  // the team is faster: an idle machine
  CHECK(omp_get_max_threads() == 2);   // restored after each loop
}

TEST_CASE("a loop started again soon after a trial keeps its choice without a new trial", "[core]") {
  const Team team(2);
  REQUIRE(kept_after_trial(1, 3) == 1);
  {
    ThreadGovernor again;  // as ADR's next load step would
    CHECK(again.threads() == 1);
    CHECK(omp_get_max_threads() == 1);
    for (int it = 0; it < 20; ++it) again.tick();
    CHECK(again.trials() == 0);
  }
  CHECK(omp_get_max_threads() == 2);
  ThreadGovernor::forget();
  ThreadGovernor fresh;
  CHECK(fresh.threads() == 1);  // a new trial, on one thread first
}

TEST_CASE("the thread governor starts its trial on one thread and restores the caller's count", "[core]") {
  const Team team(2);
  ThreadGovernor::forget();
  {
    ThreadGovernor governor;
    CHECK(governor.threads() == 1);
    CHECK(omp_get_max_threads() == 1);
    while (governor.threads() == 1) governor.tick();  // one thread for the trial's minimum time
    CHECK(omp_get_max_threads() == 2);                 // then the team's half of the trial
  }
  CHECK(omp_get_max_threads() == 2);
}

TEST_CASE("a governor inside another's loop, or switched off, leaves the thread count alone", "[core]") {
  const Team team(2);
  SECTION("nested: the outer loop governs") {
    ThreadGovernor outer;
    outer.tick();
    const int now = omp_get_max_threads();
    ThreadGovernor inner;
    for (int it = 0; it < 1000; ++it) inner.tick();
    CHECK(omp_get_max_threads() == now);
  }
  SECTION("PERINOM_THREAD_GOVERNOR=off") {
    setenv("PERINOM_THREAD_GOVERNOR", "off", 1);
    {
      ThreadGovernor governor;
      for (int it = 0; it < 3; ++it) governor.tick();
      CHECK(omp_get_max_threads() == 2);
    }
    unsetenv("PERINOM_THREAD_GOVERNOR");
  }
  SECTION("one thread: nothing to choose") {
    omp_set_num_threads(1);
    ThreadGovernor governor;
    for (int it = 0; it < 1000; ++it) governor.tick();
    CHECK(governor.threads() == 1);
    CHECK(governor.trials() == 0);
  }
}
