#include "perinom/core/timer.hpp"

namespace perinom {

void PhaseTimer::start(const std::string& name) {
  stop();
  running_ = name;
  since_ = Clock::now();
}

void PhaseTimer::stop() {
  if (running_.empty()) return;
  const double s = std::chrono::duration<double>(Clock::now() - since_).count();
  phases_.emplace_back(running_, s);
  running_.clear();
}

double PhaseTimer::total() const {
  double t = 0.0;
  for (const auto& p : phases_) t += p.second;
  return t;
}

double wall_seconds() {
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}

}  // namespace perinom
