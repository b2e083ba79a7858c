// perinom: the command line program.
//   perinom run SCENE [--out DIR] [--set dotted.key=value]... [--threads N]
//   perinom check SCENE [--set dotted.key=value]... [--spectrum]
//   perinom bench force --dimension 3 --n N [--threads T]
//   perinom material-point [--test 1..7] [--substeps S] [--out DIR]
// Exit codes: 0 success, 1 the solve did not converge, 2 bad input, 3 the solve failed.
#include <omp.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "commands.hpp"
#include "perinom/core/error.hpp"

namespace {

void usage() {
  std::fprintf(stderr,
               "usage:\n"
               "  perinom run SCENE [--out DIR] [--set dotted.key=value]... [--threads N]\n"
               "  perinom check SCENE [--set dotted.key=value]... [--spectrum]\n"
               "  perinom bench force --dimension 2|3 --n N [--threads T] [--stabilization C] [--storage auto|fused|assembled|matrix_free] [--single]\n"
               "  perinom material-point [--test 1..7] [--substeps S] [--out DIR]\n");
}

}  // namespace

int main(int argc, char** argv) {
  using namespace perinom;
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h") {
    usage();
    return args.empty() ? 2 : 0;
  }
  cli::Options opt;
  opt.command = args[0];
  try {
    for (std::size_t k = 1; k < args.size(); ++k) {
      const std::string& a = args[k];
      auto value = [&]() -> std::string {
        if (k + 1 >= args.size()) throw InputError("option " + a + " needs a value");
        return args[++k];
      };
      auto integer = [&]() {
        const std::string v = value();
        try {
          return std::stol(v);
        } catch (const std::exception&) {
          throw InputError("option " + a + ": '" + v + "' is not a whole number");
        }
      };
      if (a == "--out") opt.out = value();
      else if (a == "--set") opt.overrides.push_back(value());
      else if (a == "--threads") opt.threads = static_cast<int>(integer());
      else if (a == "--dimension") opt.dimension = static_cast<int>(integer());
      else if (a == "--n") opt.n = integer();
      else if (a == "--stabilization") {
        const std::string v = value();
        try {
          opt.stabilization = std::stod(v);
        } catch (const std::exception&) {
          throw InputError("option --stabilization: '" + v + "' is not a number");
        }
      }
      else if (a == "--storage") opt.storage = value();
      else if (a == "--test") opt.test = static_cast<int>(integer());
      else if (a == "--substeps") opt.substeps = static_cast<int>(integer());
      else if (a == "--single") opt.single_precision = true;
      else if (a == "--spectrum") opt.spectrum = true;
      else if (a.rfind("--", 0) == 0) throw InputError("unknown option " + a);
      else opt.positional.push_back(a);
    }
    if (opt.threads < 0) throw InputError("--threads must be positive");
    if (opt.threads > 0) omp_set_num_threads(opt.threads);
    if (opt.command == "run") return cli::run(opt);
    if (opt.command == "check") return cli::check(opt);
    if (opt.command == "bench") return cli::bench(opt);
    if (opt.command == "material-point") return cli::material_point(opt);
    usage();
    throw InputError("unknown command '" + opt.command + "'");
  } catch (const InputError& e) {
    std::fprintf(stderr, "perinom: error: %s\n", e.what());
    return 2;
  } catch (const SolveError& e) {
    std::fprintf(stderr, "perinom: solve failed: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "perinom: internal error: %s\n", e.what());
    return 4;
  }
}
