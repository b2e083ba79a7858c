#pragma once
// Test support: a command started in the background from a folder, and stopped the way a
// user's kill stops it (SIGKILL: no handler runs) once a condition holds.
#include <signal.h>
#include <sys/types.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <thread>

#include "slurp.hpp"

namespace test_support {

/// Runs `command` (a shell command line, its output redirected by the caller) in the
/// background from `dir`, which must exist: its process id.
inline pid_t start_in_background(const std::filesystem::path& dir, const std::string& command) {
  const std::string start = "cd '" + dir.string() + "' && { " + command + " & echo $! > pid; }";
  if (std::system(start.c_str()) != 0) throw std::runtime_error("cannot start: " + command);
  return std::stoi(slurp(dir / "pid"));
}

/// Waits (at most `seconds`) until `done` holds, lets the process go on `settle_ms` more
/// milliseconds, then kills it and waits until it is gone.
template <class Done>
void kill_when(pid_t pid, double seconds, Done done, int settle_ms = 200) {
  for (int k = 0; k < int(seconds * 10) && !done(); ++k) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  std::this_thread::sleep_for(std::chrono::milliseconds(settle_ms));
  ::kill(pid, SIGKILL);
  for (int k = 0; k < 100 && ::kill(pid, 0) == 0; ++k) std::this_thread::sleep_for(std::chrono::milliseconds(50));
}

}  // namespace test_support
