#pragma once
// The whole text of a file (empty if it cannot be read): the tests' one way to read an output;
// and a number from a JSON text.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace test_support {

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// The number after "key": in a JSON text (its first occurrence); NaN when the key is absent,
/// so that any comparison with it fails.
inline double json_number(const std::string& json, const std::string& key) {
  const auto at = json.find("\"" + key + "\": ");
  return at == std::string::npos ? NAN : std::stod(json.substr(at + key.size() + 4));
}

}  // namespace test_support
