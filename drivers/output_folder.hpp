#pragma once
// The output folder of `perinom run`: it can always be told apart whether it holds one
// finished run, a run still going or killed, or nothing of perinom's.
//   - At start the folder is created and checked writable, the marker run.incomplete is
//     written, and the files an earlier run left (summary.json, history.csv, load_steps.csv,
//     *.vtu, *.pvtu, *.pvd, probe_*.csv, snapshot CSVs NAME_NNNNNN.csv, checkpoint.bin, and *.tmp
//     of these) are removed, unless --keep; a run resumed in place (restart.hpp) spares
//     the files of the run it continues.
//   - summary.json is written last, with its "status".
//   - The marker and any .tmp file are removed on every way out the program controls (the
//     destructor runs on success, on exit codes 1 to 4 alike); only a kill leaves them.
#include <set>
#include <string>

namespace perinom::cli {

class RunFolder {
 public:
  /// The marker's file name.
  static constexpr const char* marker = "run.incomplete";

  /// Prepares `dir` as above, sparing the files named in `spare`. @throws InputError naming
  /// --out DIR if it cannot be written.
  RunFolder(std::string dir, bool keep, const std::set<std::string>& spare = {});
  ~RunFolder();
  RunFolder(const RunFolder&) = delete;
  RunFolder& operator=(const RunFolder&) = delete;

  const std::string& path() const { return dir_; }
  /// How many files of an earlier run were removed at start.
  int removed() const { return removed_; }

 private:
  std::string dir_;
  int removed_ = 0;
};

/// Whether a file name in an output folder is one `perinom run` writes (or its .tmp).
bool is_run_output(const std::string& file_name);

}  // namespace perinom::cli
