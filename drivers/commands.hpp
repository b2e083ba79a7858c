#pragma once
// The subcommands of the perinom program.
#include <string>
#include <vector>

namespace perinom::cli {

struct Options {
  std::string command, out;
  std::vector<std::string> positional, overrides;
  int threads = 0;
  int dimension = 3;
  long n = 20;
  double stabilization = 0.5;
  std::string storage = "auto";  ///< the stabilization storage (bench)
  bool single_precision = false;  ///< G's weights stored as float
  int test = 2;                   ///< material-point: seed 000 Table 2 test
  int substeps = 1000;            ///< material-point: sub-steps of the reference
  bool spectrum = false;          ///< check: also the stability check (eigenvalues of M^-1 K)
};

int run(const Options& opt);
int check(const Options& opt);
int bench(const Options& opt);
int material_point(const Options& opt);

}  // namespace perinom::cli
