#pragma once
/// @file How a long solve reports progress without knowing where the report goes.
#include <cstdint>

namespace perinom {

struct History;

/// One progress sample.
struct ProgressSample {
  std::int64_t iteration = 0;   ///< iterations (or steps) done so far, all load steps
  std::int64_t limit = 0;       ///< the iteration (or step) limit
  int load_step = 0, load_steps = 1;
  double residual = 0.0;        ///< relative residual (ADR) or 0
  double target = 0.0;          ///< the tolerance the residual must reach (ADR) or 0
  double time = 0.0;            ///< simulated time (Verlet) or 0
  std::int64_t broken = -1;     ///< bonds broken so far (Verlet with breaking), or -1
  bool step_converged = false;  ///< Newton: the sample closes a converged load step (whose row follows);
                                ///< false: from inside a step still being solved
  const History* history = nullptr;  ///< ADR's or Verlet's rows so far, for a report that writes them
};

/// Receives samples; the command line draws a bar on a terminal, plain lines otherwise.
class Progress {
 public:
  virtual ~Progress() = default;
  virtual void update(const ProgressSample& s) = 0;
  /// A step before the iterations that may take long on large scenes (once per call).
  virtual void phase(const char* /*what*/) {}
  /// Something the user should know before the iterations start (the command line prints
  /// "perinom: warning: " and it).
  virtual void warn(const char* /*what*/) {}
  virtual void finish() {}
};

}  // namespace perinom
