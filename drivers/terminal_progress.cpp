#include "terminal_progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>

#include "perinom/core/timer.hpp"
#include "diagnostics.hpp"

namespace perinom::cli {

TerminalProgress::TerminalProgress(const char* label)
    : label_(label), tty_(isatty(fileno(stdout)) != 0), start_(wall_seconds()) {}

void TerminalProgress::update(const ProgressSample& s) {
  const double now = wall_seconds(), elapsed = now - start_;
  // ETA: iterations left for Verlet; for ADR, the decade rate of the residual so far.
  double left = -1.0, fraction = double(s.iteration) / std::max<std::int64_t>(1, s.limit);
  if (s.target > 0.0 && s.residual > 0.0) {
    const double lr = std::log10(s.residual), lt = std::log10(s.target);
    if (!have_first_) first_log_residual_ = lr, have_first_ = true;
    const double done = first_log_residual_ - lr, todo = lr - lt;
    if (done > 0.0) {
      left = std::max(0.0, elapsed * todo / done);
      fraction = std::clamp(done / (done + std::max(0.0, todo)), 0.0, 1.0);
    }
    // A single solve stops at its iteration limit whatever the residual's trend ("~17582 s
    // left" two seconds before max_iterations ended it).
    if (left >= 0.0 && s.load_steps <= 1 && s.limit > 0 && s.iteration > 0)
      left = std::min(left, elapsed * double(std::max<std::int64_t>(0, s.limit - s.iteration)) / double(s.iteration));
  } else if (s.iteration > 0 && s.limit > 0) {
    left = elapsed * double(s.limit - s.iteration) / double(s.iteration);
  }
  if (tty_) {
    if (now - last_print_ < 0.1) return;
    const int width = 30, filled = static_cast<int>(fraction * width);
    static const char bar[] = "##############################";  // width characters; no allocation
    std::printf("\r%s [%-*.*s] it %lld", label_, width, filled, bar, static_cast<long long>(s.iteration));
    if (s.load_steps > 1) std::printf(" step %d/%d", s.load_step, s.load_steps);
    if (s.target > 0.0) std::printf(" residual %.2e -> %.0e", s.residual, s.target);
    if (left >= 0.0) std::printf(" left ~%.0fs ", left);
    std::fflush(stdout);
  } else {
    if (now - last_print_ < 5.0) return;
    std::printf("%s: iteration %lld", label_, static_cast<long long>(s.iteration));
    if (s.load_steps > 1) std::printf(", load step %d/%d", s.load_step, s.load_steps);
    if (s.target > 0.0) std::printf(", residual %.3e (target %.1e)", s.residual, s.target);
    if (s.time > 0.0) std::printf(", t = %.4g s", s.time);
    if (s.broken >= 0) std::printf(", %lld bonds broken", static_cast<long long>(s.broken));
    if (left >= 0.0) std::printf(", ~%.0f s left", left);
    std::printf("\n");
    std::fflush(stdout);
  }
  last_print_ = now;
  printed_ = true;
}

void TerminalProgress::finish() {
  if (tty_ && printed_) std::printf("\n");
  printed_ = false;
}

void TerminalProgress::phase(const char* what) {
  std::printf("perinom: %s\n", what);
  std::fflush(stdout);
}

void TerminalProgress::warn(const char* what) {
  cli::warn("%s", what);
  std::fflush(stdout);
}

}  // namespace perinom::cli
