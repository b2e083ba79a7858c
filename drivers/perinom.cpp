// perinom: the command line program.
//   perinom run SCENE [--out DIR] [--set dotted.key=value]... [--threads N] [--keep] [--max-memory SIZE] [--restart DIR]
//               [--petsc-options 'OPTIONS']
//   perinom check SCENE [--set dotted.key=value]... [--max-memory SIZE] [--spectrum] [--ranks R]
//   perinom bench force --dimension 3 --n N [--threads T]
//   perinom material-point [--test 1..7] [--substeps S] [--out DIR]
// Exit codes: 0 success, 1 the solve did not converge, 2 bad input, 3 the solve failed.
#include <omp.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "commands.hpp"
#include "perinom/core/error.hpp"
#include "perinom/distributed/ranks.hpp"
#include "perinom/solvers/petsc.hpp"

namespace {

void usage() {
  std::fprintf(stderr,
               "usage:\n"
               "  perinom run SCENE [--out DIR] [--set dotted.key=value]... [--threads N] [--keep] [--max-memory SIZE]\n"
               "              [--restart DIR] [--petsc-options 'OPTIONS']\n"
               "  perinom check SCENE [--set dotted.key=value]... [--max-memory SIZE] [--spectrum] [--ranks R]\n"
               "  perinom bench force --dimension 2|3 --n N [--threads T] [--stabilization C] [--storage auto|fused|assembled|matrix_free] [--single] [--check]\n"
               "    (under mpirun -np R: the distributed force, R ranks; --check compares it with the serial one)\n"
               "  perinom bench refresh --dimension 2|3 --n N --bonds B [--threads T]\n"
               "  perinom material-point [--test 1..7] [--substeps S] [--out DIR]\n");
}

/// An error's exit code. Under mpirun the error may be some ranks' alone (a singular fit in
/// one rank's part): every rank is ended with it (abort_ranks), never left waiting.
int failed(int code) {
  std::fflush(nullptr);
  perinom::abort_ranks(code);
  return code;
}

/// An option another command reads is bad input here: `run --spectrum` ran no stability
/// check and `check --out x --keep` ignored both, with exit 0.
void refuse_foreign_options(const perinom::cli::Options& opt, const std::vector<std::string>& given) {
  static const std::map<std::string, std::set<std::string>> own = {
      {"run", {"--out", "--restart", "--set", "--threads", "--keep", "--petsc-options", "--max-memory"}},
      {"check", {"--set", "--threads", "--max-memory", "--spectrum", "--ranks"}},
      {"bench", {"--threads", "--dimension", "--n", "--stabilization", "--storage", "--single", "--bonds", "--check"}},
      {"material-point", {"--threads", "--test", "--substeps", "--out"}}};
  const auto it = own.find(opt.command);
  if (it == own.end()) return;  // an unknown command: said after
  const std::string sub = opt.command == "bench" && !opt.positional.empty() ? opt.positional[0] : "";
  for (const std::string& a : given) {
    const bool foreign = !it->second.count(a) || (sub == "force" && a == "--bonds") ||
                         (sub == "refresh" && (a == "--check" || a == "--storage" || a == "--single" ||
                                               a == "--stabilization"));
    if (foreign)
      throw perinom::InputError("option " + a + " is not an option of 'perinom " + opt.command + (sub.empty() ? "" : " " + sub) +
                       "' (see perinom --help)");
  }
}

/// Ends PETSc (and MPI) however main returns, if a solve started it.
struct PetscEnd {
  ~PetscEnd() { perinom::finalize_petsc(); }
};

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
  const PetscEnd petsc_end;
  bool dispatched = false;  // before a command runs, every MPI rank reads the same options alike
  try {
    // Only run and the force benchmark are distributed so far (issue 19): any other command
    // under mpirun would do the whole work on every rank and write the same files.
    const bool distributed = args[0] == "run" || (args[0] == "bench" && args.size() > 1 && args[1] == "force");
    if (mpirun_processes() > 1 && !distributed)
      throw InputErrorOnEveryRank("perinom " + args[0] + " runs on one MPI rank: of the distributed path only 'perinom run' "
                       "and 'perinom bench force' are built yet, and mpirun -np " + std::to_string(mpirun_processes()) +
                       " would do the whole work on every rank (run it without mpirun; solver.linear_solver mumps "
                       "or gamg uses PETSc on one rank)");
    std::vector<std::string> given;  // the options, for the command's own (below)
    std::set<std::string> valued;    // the options given a value so far
    for (std::size_t k = 1; k < args.size(); ++k) {
      const std::string& a = args[k];
      if (a.rfind("--", 0) == 0) given.push_back(a);
      auto value = [&]() -> std::string {
        if (k + 1 >= args.size()) throw InputError("option " + a + " needs a value");
        // A second value was silently the one used (`--restart a --restart b` resumed b).
        if (a != "--set" && !valued.insert(a).second)
          throw InputError("option " + a + " is given twice: it takes one value (only --set may be repeated)");
        return args[++k];
      };
      // Whole numbers and reals are read strictly: all of the text, within the bounds.
      auto integer = [&](long lo, long hi) {
        const std::string v = value();
        long n = 0;
        const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), n);
        if (ec == std::errc::result_out_of_range || (ec == std::errc() && end == v.data() + v.size() && (n < lo || n > hi)))
          throw InputError("option " + a + ": " + v + " is out of range (" + std::to_string(lo) + " to " +
                           std::to_string(hi) + ")");
        if (ec != std::errc() || end != v.data() + v.size() || v.empty())
          throw InputError("option " + a + ": '" + v + "' is not a whole number");
        return n;
      };
      if (a == "--out") {
        opt.out = value();
        if (opt.out.empty()) throw InputError("option --out: the folder name is empty");
      } else if (a == "--restart") {
        opt.restart = value();
        if (opt.restart.empty()) throw InputError("option --restart: the folder name is empty");
      } else if (a == "--set") opt.overrides.push_back(value());
      else if (a == "--threads") opt.threads = static_cast<int>(integer(1, cli::max_threads));
      else if (a == "--dimension") opt.dimension = static_cast<int>(integer(2, 3));
      else if (a == "--n") opt.n = integer(4, 100000);
      else if (a == "--stabilization") {
        const std::string v = value();
        char* end = nullptr;
        opt.stabilization = v.empty() ? NAN : std::strtod(v.c_str(), &end);
        if (v.empty() || end != v.c_str() + v.size() || !std::isfinite(opt.stabilization))
          throw InputError("option --stabilization: '" + v + "' is not a finite number");
        if (opt.stabilization < 0.0) throw InputError("option --stabilization: must be zero or positive");
      }
      else if (a == "--storage") opt.storage = value();
      else if (a == "--bonds") opt.bonds = integer(1, 1000000000);
      else if (a == "--test") opt.test = static_cast<int>(integer(1, 7));
      else if (a == "--substeps") opt.substeps = static_cast<int>(integer(1, 100000000));
      else if (a == "--single") opt.single_precision = true;
      else if (a == "--spectrum") opt.spectrum = true;
      else if (a == "--check") opt.check = true;
      else if (a == "--ranks") opt.ranks = static_cast<int>(integer(1, 1000000));
      else if (a == "--keep") opt.keep = true;
      else if (a == "--petsc-options") set_petsc_options(value());
      else if (a == "--max-memory") {
        // A whole number of bytes, or of KiB, MiB, GiB, TiB with the suffix K, M, G or T.
        const std::string v = value();
        const std::size_t digits = v.find_first_not_of("0123456789");
        const std::string unit = digits == std::string::npos ? "" : v.substr(digits);
        const double scale = unit == "" ? 1.0 : unit == "K" ? 1024.0 : unit == "M" ? 1048576.0
                           : unit == "G" ? 1073741824.0 : unit == "T" ? 1099511627776.0 : 0.0;
        if (digits == 0 || scale == 0.0 || v.size() - unit.size() > 15)
          throw InputError("option --max-memory: '" + v + "' is not a size (bytes, or a whole number with K, M, G or T)");
        opt.max_memory = std::stod(v.substr(0, digits)) * scale;
        if (opt.max_memory <= 0.0) throw InputError("option --max-memory: must be positive");
      }
      else if (a.rfind("--", 0) == 0) throw InputError("unknown option " + a);
      else opt.positional.push_back(a);
    }
    refuse_foreign_options(opt, given);
    if (opt.threads > 0) omp_set_num_threads(opt.threads);
    else if (omp_get_max_threads() > cli::max_threads) omp_set_num_threads(cli::max_threads);
    dispatched = true;
    if (opt.command == "run") return mpirun_processes() > 1 ? cli::run_distributed(opt) : cli::run(opt);
    if (opt.command == "check") return cli::check(opt);
    if (opt.command == "bench") return cli::bench(opt);
    if (opt.command == "material-point") return cli::material_point(opt);
    usage();
    throw InputError("unknown command '" + opt.command + "'");
  } catch (const InputErrorOnEveryRank& e) {
    if (mpirun_rank() == 0) std::fprintf(stderr, "perinom: error: %s\n", e.what());
    return 2;
  } catch (const InputError& e) {
    if (!dispatched && mpirun_processes() > 1) {  // a bad option: every rank's alike, said once
      if (mpirun_rank() == 0) std::fprintf(stderr, "perinom: error: %s\n", e.what());
      return 2;
    }
    std::fprintf(stderr, "perinom: error: %s\n", e.what());
    return failed(2);
  } catch (const SolveErrorOnEveryRank& e) {
    if (mpirun_rank() == 0) std::fprintf(stderr, "perinom: solve failed: %s\n", e.what());
    return 3;
  } catch (const SolveError& e) {
    std::fprintf(stderr, "perinom: solve failed: %s\n", e.what());
    return failed(3);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "perinom: internal error: %s\n", e.what());
    return failed(4);
  }
}
