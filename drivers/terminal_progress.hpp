#pragma once
// Progress for the command line: a one-line bar with an estimate of the time left on a
// terminal, plain periodic lines otherwise (logs, CI).
#include <cstdio>

#include "perinom/core/progress.hpp"

namespace perinom::cli {

class TerminalProgress : public Progress {
 public:
  explicit TerminalProgress(const char* label);
  void update(const ProgressSample& s) override;
  void finish() override;
  void phase(const char* what) override;
  void warn(const char* what) override;

 private:
  const char* label_;
  bool tty_;
  double start_, last_print_ = -1e300, first_log_residual_ = 0.0;
  bool have_first_ = false, printed_ = false;
};

}  // namespace perinom::cli
