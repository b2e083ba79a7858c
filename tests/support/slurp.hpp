#pragma once
// The whole text of a file (empty if it cannot be read): the tests' one way to read an output.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace test_support {

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace test_support
