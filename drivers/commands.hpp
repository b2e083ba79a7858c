#pragma once
// The subcommands of the perinom program.
#include <string>
#include <vector>

#include "perinom/core/error.hpp"

namespace perinom {
struct PointCloud;
}

namespace perinom::cli {

/// The most OpenMP threads --threads accepts (more than any machine perinom runs on has
/// cores; a mistyped 10000 would make every parallel region a crowd).
constexpr int max_threads = 1024;

struct Options {
  std::string command, out;
  std::vector<std::string> positional, overrides;
  int threads = 0;                ///< 0: the OpenMP default (the available cores)
  bool keep = false;              ///< run: keep an earlier run's files in the output folder
  std::string restart;            ///< run: resume from the checkpoint in this folder (--restart)
  double max_memory = 0.0;        ///< bytes a scene may need (--max-memory); 0: the available memory
  int dimension = 3;
  long n = 20;
  double stabilization = 0.5;
  std::string storage = "auto";  ///< the stabilization storage (bench)
  bool single_precision = false;  ///< G's weights stored as float
  long bonds = 1;                 ///< bench refresh: bonds to break
  int test = 2;                   ///< material-point: seed 000 Table 2 test
  int substeps = 1000;            ///< material-point: sub-steps of the reference
  bool spectrum = false;          ///< check: also the stability check (eigenvalues of M^-1 K)
  int ranks = 0;                  ///< check: report a partition into this many ranks (0: none)
  bool check = false;             ///< bench force: the distributed force against the serial one
};

int run(const Options& opt);
int check(const Options& opt);
int bench(const Options& opt);
int material_point(const Options& opt);
/// perinom bench force on the ranks mpirun started (one without it), the cloud split by
/// local_part; --check compares the force with the serial one (exit 1 when it differs).
/// perinom run under mpirun -np R (R > 1): the distributed run (run_distributed.cpp).
int run_distributed(const Options& opt);
int bench_force_distributed(const Options& opt, const PointCloud& cloud);

}  // namespace perinom::cli
