#pragma once
// The output folder of `perinom run`: it can always be told apart whether it holds one
// finished run, a run still going or killed, or nothing of perinom's; and a run removes
// only files a perinom run wrote there, never a user's own.
//   - At start the folder is created and checked writable, refused while another perinom
//     writes it (its marker names a live perinom process, not a zombie), and the marker
//     run.incomplete is written. The files an earlier run wrote are removed, unless --keep: those its
//     manifest perinom.files lists, and, after a killed run (its marker left, no manifest),
//     those named as a run's output (summary.json, history.csv, load_steps.csv, *.vtu,
//     *.pvtu, *.pvd, probe_*.csv, snapshot CSVs NAME_NNNNNN.csv, checkpoint.bin) written
//     since its marker. Any *.tmp of these goes too. A run resumed in place (restart.hpp)
//     spares the files of the run it continues. Files named like a run's output that no run
//     recorded (a reference.vtu of the user's, a folder of an older perinom) are left in
//     place and listed (foreign()), unless this run could write over them: a foreign
//     summary.json, history.csv, load_steps.csv or checkpoint.bin, or a name the run says it
//     may write (its scene's snapshots NAME_*, series, probes), is refused before anything is
//     written (a user's summary.json was overwritten while the warning said it was left in
//     place).
//   - summary.json is written last, with its "status".
//   - On every way out the program controls (the destructor runs on success, on exit codes
//     1 to 4 alike) the manifest is written (this run's outputs: written since its marker,
//     the spared files, and with --keep the earlier manifest's), and the marker and any
//     .tmp file are removed; only a kill leaves them.
#include <filesystem>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include "perinom/core/error.hpp"
#include "perinom/scene/scene.hpp"

namespace perinom::cli {

class RunFolder {
 public:
  /// The marker's and the manifest's file names.
  static constexpr const char* marker = "run.incomplete";
  static constexpr const char* manifest = "perinom.files";

  /// Whether this run writes a file of that name (beyond the names every run may write).
  using OutputNames = std::function<bool(const std::string&)>;

  /// Prepares `dir` as above, sparing the files named in `spare`. @throws InputError naming
  /// --out DIR if it cannot be written, another perinom run is writing it, or it holds a file
  /// of the user's named like this run's outputs.
  RunFolder(std::string dir, bool keep, const std::set<std::string>& spare = {}, const OutputNames& writes = {});
  ~RunFolder();
  RunFolder(const RunFolder&) = delete;
  RunFolder& operator=(const RunFolder&) = delete;

  const std::string& path() const { return dir_; }
  /// How many files of an earlier run were removed at start.
  int removed() const { return removed_; }
  /// The files named like a run's output that no run recorded writing, left in place.
  const std::vector<std::string>& foreign() const { return foreign_; }
  /// Prints what the start did: the files removed, the foreign ones left.
  void announce() const;
  /// For an error that ends the run before its summary.json: writes one with status "error",
  /// the scene's file and name, `error` and the exit code (a long run whose first snapshot
  /// could not be written left a history and no summary). Nothing when this run wrote its
  /// summary already, or when it cannot be written (the marker then stays: ~RunFolder).
  void record_error(const Scene& scene, const std::string& error, int exit_code) const {
    record_error(scene.source, scene.name, error, exit_code);
  }
  /// The same, naming the scene file as given and its name ("": not read, left out).
  void record_error(const std::string& scene_file, const std::string& name, const std::string& error,
                    int exit_code) const;
  /// Whether `dir` holds a finished perinom run: its manifest and no marker.
  static bool holds_finished_run(const std::string& dir);
  /// Writes the error summary (as record_error) into `dir` and nothing else: for a run refused
  /// before it had a folder, where a finished run's summary would pass for this run's. Its
  /// other files stay (a typo in --set is no reason to lose them) and its manifest, which
  /// lists summary.json already, still names them all for the next run to remove.
  static void write_error_summary(const std::string& dir, const std::string& scene_file, const std::string& name,
                                  const std::string& error, int exit_code);
  /// Runs `body`; an error it throws is recorded (record_error, with the exit code perinom
  /// gives it: 2 bad input or an output that cannot be written, 3 a failed solve, 4 other)
  /// and thrown on.
  template <class Body>
  auto recording_errors(const Scene& scene, Body body) const {
    try {
      return body();
    } catch (const InputError& e) {
      record_error(scene, e.what(), 2);
      throw;
    } catch (const SolveError& e) {
      record_error(scene, e.what(), 3);
      throw;
    } catch (const std::exception& e) {
      record_error(scene, e.what(), 4);
      throw;
    }
  }

 private:
  std::string dir_;
  int removed_ = 0;
  std::vector<std::string> foreign_;
  std::set<std::string> carried_;  ///< names the manifest keeps whatever their time: spared, kept
  std::filesystem::file_time_type start_;
};

/// Whether a file name in an output folder is one `perinom run` writes (or its .tmp).
bool is_run_output(const std::string& file_name);

/// Whether a run of `scene` writes a file of that name: its snapshots (NAME_NNNNNN.vtu, .csv,
/// .pvtu), its series NAME.pvd and its probes' files.
bool scene_writes(const Scene& scene, const std::string& file_name);

}  // namespace perinom::cli
