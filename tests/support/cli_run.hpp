#pragma once
// Test support: the perinom program run as a user runs it, in a scratch folder, and the
// check that bad input ends in exit code 2 with one clear error line. Global names: these
// tests include no perinom header, whose namespace the function perinom would clash with.
#include <catch2/catch.hpp>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#ifndef PERINOM_EXE
#error "PERINOM_EXE must name the perinom binary (a string literal)"
#endif

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

inline std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

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

