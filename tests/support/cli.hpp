#pragma once
// Test support for the perinom program as a user runs it: a scratch folder, the tiny valid
// scene, running the real binary (PERINOM_EXE, set by tests/CMakeLists.txt) and checking
// that bad input ends in exit code 2 with one clear line on stderr.
#include <catch2/catch.hpp>
#include <stdlib.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>
#include "slurp.hpp"

#ifndef PERINOM_EXE
#error "PERINOM_EXE must name the perinom binary (a string literal)"
#endif

namespace cli_test {

namespace fs = std::filesystem;

/// A fresh folder under the system temp folder, removed with its contents at scope end.
struct ScratchDir {
  fs::path path;
  ScratchDir() {
    std::string pattern = (fs::temp_directory_path() / "perinom_cli_XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp " + pattern);
    path = pattern;
  }
  ~ScratchDir() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
};

/// A 4 x 4 cloud from a point file cloud.csv (spacing 1 mm, volumes 1e-6), held at its bottom
/// row and pulled at its top, checkpointed every 5 iterations.
inline const std::string point_file_scene = R"(name: points
dimension: 2
geometry: {points: cloud.csv}
discretization: {dx: 0.001, horizon: {ratio: 2.015}}
material: {type: linear_elastic, E: 1.0e9, nu: 0.25, density: 1000.0}
model: {formulation: classical, operator_order: 1}
boundary:
  - {region: {box: {min: [0.0, 0.0], max: [0.004, 0.001]}}, fix: [x, y]}
  - {region: {box: {min: [0.0, 0.003], max: [0.004, 0.004]}}, displacement: {y: 1.0e-6}}
output: {checkpoint_every: 5}
)";

/// A valid 2-D scene: 10 x 10 particles, bottom fixed, pressure on top, two probes.
inline const std::string tiny_scene = R"(name: tiny
dimension: 2
geometry:
  box: {min: [0.0, 0.0], max: [0.01, 0.01]}
discretization:
  dx: 0.001
  horizon: {ratio: 3.015}
material:
  type: linear_elastic
  E: 1.0e9
  nu: 0.25
  density: 1000.0
boundary:
  - region: bottom
    fix: [x, y]
  - region: top
    pressure: 1.0e6
solver:
  type: adr
  tolerance: 1.0e-6
  displacement_tolerance: 1.0e-6
probes:
  - name: top_uy
    point: [0.005, 0.01]
    component: y
  - name: mid
    line: {from: [0.005, 0.0], to: [0.005, 0.01]}
    field: stress
    component: yy
)";

/// The scene with the one occurrence of `from` replaced by `to`.
inline std::string with(const std::string& scene, const std::string& from, const std::string& to) {
  const auto at = scene.find(from);
  REQUIRE(at != std::string::npos);
  REQUIRE(scene.find(from, at + 1) == std::string::npos);
  return scene.substr(0, at) + to + scene.substr(at + from.size());
}

/// The 1-based line of the first occurrence of `text` in the scene.
inline int line_of(const std::string& scene, const std::string& text) {
  const auto at = scene.find(text);
  REQUIRE(at != std::string::npos);
  return 1 + static_cast<int>(std::count(scene.begin(), scene.begin() + at, '\n'));
}

using test_support::json_number;
using test_support::slurp;

struct Outcome {
  int exit_code = -1;
  std::string out, err;
};

/// Runs `perinom ARGS` inside the folder (so scene.yaml is named as such in messages).
inline Outcome perinom(const ScratchDir& dir, const std::string& args) {
  const std::string q = "'" + dir.path.string() + "'";
  const std::string command = "cd " + q + " && '" PERINOM_EXE "' " + args + " >" + q +
                              "/stdout.txt 2>" + q + "/stderr.txt";
  const int status = std::system(command.c_str());
  Outcome o;
  o.exit_code = (status != -1 && WIFEXITED(status)) ? WEXITSTATUS(status) : -1;
  o.out = slurp(dir.path / "stdout.txt");
  o.err = slurp(dir.path / "stderr.txt");
  return o;
}

/// Bad input: exit code 2 and exactly one "perinom: error: ..." line holding every needle.
inline void require_one_clear_error(const Outcome& o, std::initializer_list<std::string> needles) {
  INFO("stderr: " << o.err);
  INFO("stdout: " << o.out);
  CHECK(o.exit_code == 2);
  std::vector<std::string> lines;
  std::istringstream in(o.err);
  for (std::string l; std::getline(in, l);)
    if (!l.empty()) lines.push_back(l);
  REQUIRE(lines.size() == 1);
  CHECK(lines[0].rfind("perinom: error: ", 0) == 0);
  for (const auto& n : needles) CHECK(lines[0].find(n) != std::string::npos);
}

/// Writes the scene and checks that both `check` and `run` reject it with the needles.
inline void require_rejected(const std::string& scene, std::initializer_list<std::string> needles,
                      const std::string& extra = "") {
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << scene;
  SECTION("perinom check") { require_one_clear_error(perinom(dir, "check scene.yaml " + extra), needles); }
  SECTION("perinom run") {
    require_one_clear_error(perinom(dir, "run scene.yaml --out out " + extra), needles);
    // Never a result: no summary, or (an error found after the folder was prepared, while
    // building) one that says the run ended in error.
    const fs::path summary = dir.path / "out" / "summary.json";
    if (fs::exists(summary)) CHECK(slurp(summary).find("\"status\": \"error\"") != std::string::npos);
  }
}

/// Writes the scene and checks that `check` (with `extra`) accepts it: exit code 0.
inline void require_valid(const std::string& scene, const std::string& extra = "") {
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << scene;
  const Outcome o = perinom(dir, "check scene.yaml " + extra);
  INFO("stderr: " << o.err);
  CHECK(o.exit_code == 0);
}

/// "scene.yaml:N: key" for the line of `text` in the scene.
inline std::string at_line(const std::string& scene, const std::string& text, const std::string& key) {
  return "scene.yaml:" + std::to_string(line_of(scene, text)) + ": " + key;
}


}  // namespace cli_test
