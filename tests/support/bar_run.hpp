#pragma once
// Test support: the vibrating bar of the examples run by the real perinom binary, each run in
// a fresh folder of its own (concurrent test runs on one machine must not share one), for the
// CLI tests of the stability check and of Verlet's energy balance.
#include <catch2/catch.hpp>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include "slurp.hpp"

namespace bar_test {

namespace fs = std::filesystem;

/// A fresh folder of its own under the temp folder (concurrent test runs on one machine
/// must not share one), removed with its contents when the last Outcome holding it goes.
struct Scratch {
  fs::path path;
  explicit Scratch(const std::string& name) {
    std::string pattern = (fs::temp_directory_path() / (name + "_XXXXXX")).string();
    if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp " + pattern);
    path = pattern;
  }
  ~Scratch() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
};

struct Outcome {
  int exit_code = -1;
  std::string out, err;
  fs::path dir;
  std::shared_ptr<Scratch> scratch;
};

using test_support::slurp;

/// Runs `perinom COMMAND examples/vibrating_bar.yaml --set ...` in a fresh folder (kept
/// while the Outcome lives, for the test's reads).
inline Outcome bar(const std::string& name, const std::string& command, const std::string& sets) {
  auto scratch = std::make_shared<Scratch>("perinom_bar_" + name);
  const fs::path d = scratch->path;
  const std::string cmd = "cd '" + d.string() + "' && '" PERINOM_EXE "' " + command + " '" PERINOM_SOURCE_DIR
                          "/examples/vibrating_bar.yaml' " + sets + " >out.txt 2>err.txt";
  const int status = std::system(cmd.c_str());
  Outcome o;
  o.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  o.out = slurp(d / "out.txt");
  o.err = slurp(d / "err.txt");
  o.dir = d;
  o.scratch = scratch;
  return o;
}

}  // namespace bar_test
