#pragma once
// Test support: a load path's step table (load_steps.csv) read as columns by name, for the CLI
// tests of load paths that break bonds.
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace cli_test {

/// load_steps.csv as columns by name.
inline std::map<std::string, std::vector<double>> columns(const std::string& csv) {
  std::istringstream in(csv);
  std::string line, name;
  std::getline(in, line);
  std::vector<std::string> names;
  std::istringstream head(line);
  while (std::getline(head, name, ',')) names.push_back(name);
  std::map<std::string, std::vector<double>> out;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::string cell;
    for (std::size_t c = 0; c < names.size() && std::getline(row, cell, ','); ++c) out[names[c]].push_back(std::stod(cell));
  }
  return out;
}

}  // namespace cli_test
