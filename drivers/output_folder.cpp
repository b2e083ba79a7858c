#include "output_folder.hpp"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>

#include "diagnostics.hpp"
#include "perinom/core/error.hpp"
#include "perinom/io/json_writer.hpp"

namespace perinom::cli {
namespace {

namespace fs = std::filesystem;

bool ends_with(const std::string& s, const std::string& end) {
  return s.size() >= end.size() && s.compare(s.size() - end.size(), end.size(), end) == 0;
}

/// The output names a run may write whatever its scene.
bool always_written(const std::string& file_name) {
  return file_name == "summary.json" || file_name == "history.csv" || file_name == "load_steps.csv" ||
         file_name == "checkpoint.bin";
}

/// The names an earlier run's manifest lists (none without one).
std::set<std::string> read_manifest(const std::string& dir) {
  std::set<std::string> names;
  std::ifstream f(dir + "/" + RunFolder::manifest);
  for (std::string line; std::getline(f, line);)
    if (!line.empty() && line[0] != '#') names.insert(line);
  return names;
}

/// Removes the .tmp files of run outputs; returns how many.
int remove_temporaries(const std::string& dir) {
  int removed = 0;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    std::error_code gone;
    if (ends_with(name, ".tmp") && is_run_output(name) && entry.is_regular_file(gone) && fs::remove(entry.path(), gone))
      ++removed;
  }
  return removed;
}

/// The process a marker names ("... (process 1234) ..."), 0 if none.
long marker_process(const std::string& path) {
  std::ifstream f(path);
  const std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  const std::size_t at = text.find("(process ");
  return at == std::string::npos ? 0 : std::atol(text.c_str() + at + 9);
}

/// The first line of /proc/PID/comm ("" if it cannot be read).
std::string command_of(const std::string& pid) {
  std::ifstream f("/proc/" + pid + "/comm");
  std::string name;
  std::getline(f, name);
  return name;
}

/// Whether /proc/PID/stat says the process has ended and waits to be reaped (state Z or X):
/// a run killed by `timeout -s KILL` stays such a zombie until its parent waits for it, and
/// kill(pid, 0) still finds it.
bool ended(const std::string& pid) {
  std::ifstream f("/proc/" + pid + "/stat");
  std::string stat;
  std::getline(f, stat);
  const std::size_t name_end = stat.rfind(')');  // the command name may hold spaces and ')'
  if (name_end == std::string::npos || name_end + 2 >= stat.size()) return false;
  const char state = stat[name_end + 2];
  return state == 'Z' || state == 'X';
}

/// Whether process `pid` is alive and a perinom (its command name this one's; one whose name
/// cannot be read counts as a perinom: refusing is the safe error, and the message says how
/// to go on).
bool running_perinom(long pid) {
  if (pid <= 0 || pid == ::getpid() || (::kill(static_cast<pid_t>(pid), 0) != 0 && errno != EPERM)) return false;
  if (ended(std::to_string(pid))) return false;
  const std::string other = command_of(std::to_string(pid));
  return other.empty() || other == command_of("self");
}

}  // namespace

bool is_run_output(const std::string& file_name) {
  std::string name = file_name;
  if (ends_with(name, ".tmp")) name.resize(name.size() - 4);
  if (always_written(name)) return true;
  if (ends_with(name, ".vtu") || ends_with(name, ".pvtu") || ends_with(name, ".pvd")) return true;
  if (!ends_with(name, ".csv")) return false;
  if (name.rfind("probe_", 0) == 0) return true;
  // A snapshot's CSV: NAME_ and at least six digits (the .vtu's index).
  const std::string stem = name.substr(0, name.size() - 4);
  const std::size_t underscore = stem.rfind('_');
  return underscore != std::string::npos && stem.size() - underscore - 1 >= 6 &&
         stem.find_first_not_of("0123456789", underscore + 1) == std::string::npos;
}

bool scene_writes(const Scene& scene, const std::string& file_name) {
  if (file_name == scene.name + ".pvd" || file_name.rfind(scene.name + "_", 0) == 0) return true;
  for (const ProbeSpec& probe : scene.probes)
    if (file_name == "probe_" + probe.name + ".csv" || file_name == "probe_" + probe.name + "_history.csv") return true;
  return false;
}

RunFolder::RunFolder(std::string dir, bool keep, const std::set<std::string>& spare, const OutputNames& writes)
    : dir_(std::move(dir)) {
  std::error_code made, ec;
  fs::create_directories(dir_, made);
  const std::string path = dir_ + "/" + marker;
  // What the earlier run recorded: its manifest, or, if its marker is left (a run going on,
  // refused below, or killed), the start the marker keeps.
  const std::set<std::string> earlier = read_manifest(dir_);
  std::error_code none;
  const bool marked = fs::is_regular_file(path, none);
  // A marker of a run going on: two runs in one folder would mix their files (a sweep of
  // `--set` runs sharing the default out/NAME: the second removed the first's history and
  // marker, and the folder ended with one run's summary and the other's history).
  if (const long pid = marked ? marker_process(path) : 0; running_perinom(pid))
    throw InputError("--out " + dir_ + ": another perinom run (process " + std::to_string(pid) +
                     ") is writing this folder: give this run another --out, or wait for that one to end (if no "
                     "perinom runs, remove " + path + ")");
  const fs::file_time_type killed_at = marked ? fs::last_write_time(path, none) : fs::file_time_type::max();
  // Whether a file named like an output is an earlier run's: its manifest lists it, or a
  // killed run's marker is older than it.
  const auto earlier_run_wrote = [&](const fs::directory_entry& entry, const std::string& name) {
    std::error_code e;
    return earlier.count(name) || (marked && !none && entry.last_write_time(e) >= killed_at && !e);
  };
  // Before anything is written: a file of the user's that this run would write over is refused.
  std::vector<std::string> claimed;
  for (const auto& entry : fs::directory_iterator(dir_, ec)) {
    const std::string name = entry.path().filename().string();
    std::error_code e;
    if (!entry.is_regular_file(e) || !is_run_output(name) || ends_with(name, ".tmp") || spare.count(name)) continue;
    if (!earlier_run_wrote(entry, name) && (always_written(name) || (writes && writes(name)))) claimed.push_back(name);
  }
  if (!claimed.empty()) {
    std::sort(claimed.begin(), claimed.end());
    std::string list;
    for (const std::string& n : claimed) list += (list.empty() ? "" : ", ") + n;
    // Named like this scene's outputs, not necessarily one this run writes (a stray
    // NAME_000007.vtu where the run writes NAME_000000 alone was said to be written over).
    const bool many = claimed.size() > 1;
    throw InputError("--out " + dir_ + " holds " + list + ", which no perinom run recorded writing there and which " +
                     (many ? "are" : "is") + " named like this run's output files (summary, histories, checkpoint, or "
                     "this scene's snapshots, series and probes): " + (many ? "they" : "it") + " could be written over "
                     "or taken for this run's: move " + (many ? "them" : "it") + ", or give this run another --out");
  }
  {
    std::ofstream f(path, std::ios::trunc);
    f << "perinom run in progress (process " << ::getpid()
      << "); if no perinom is running, the run that wrote this folder was killed\n";
    if (made || ec || !f.flush()) {  // with the reason (an --out that is a file said nothing more)
      const std::string why = made ? made.message() : ec ? ec.message() : std::strerror(errno);
      throw InputError("--out " + dir_ + ": the output folder cannot be created or written (" + why + ")");
    }
  }
  start_ = fs::last_write_time(path, ec);
  removed_ = remove_temporaries(dir_);
  for (const auto& entry : fs::directory_iterator(dir_, ec)) {
    const std::string name = entry.path().filename().string();
    std::error_code e;
    if (!entry.is_regular_file(e) || !is_run_output(name) || ends_with(name, ".tmp")) continue;
    if (spare.count(name)) {
      carried_.insert(name);
      continue;
    }
    if (!earlier_run_wrote(entry, name)) foreign_.push_back(name);
    else if (keep) carried_.insert(name);
    else if (fs::remove(entry.path(), e)) ++removed_;
  }
  std::sort(foreign_.begin(), foreign_.end());
}

namespace {

/// Whether `name` in `dir` was written since `start` (by this run).
bool written_since(const std::string& dir, const std::string& name, fs::file_time_type start) {
  std::error_code e;
  const fs::path path = fs::path(dir) / name;
  return fs::is_regular_file(path, e) && fs::last_write_time(path, e) >= start && !e;
}

}  // namespace

bool RunFolder::holds_finished_run(const std::string& dir) {
  std::error_code e;
  return fs::is_regular_file(fs::path(dir) / manifest, e) && !fs::exists(fs::path(dir) / marker, e);
}

void RunFolder::record_error(const std::string& scene_file, const std::string& name, const std::string& error,
                             int exit_code) const {
  if (written_since(dir_, "summary.json", start_)) return;
  write_error_summary(dir_, scene_file, name, error, exit_code);
}

void RunFolder::write_error_summary(const std::string& dir, const std::string& scene_file, const std::string& name,
                                    const std::string& error, int exit_code) {
  io::Json summary = io::Json::object();
  summary["status"] = std::string("error");
  summary["scene"] = scene_file;
  if (!name.empty()) summary["name"] = name;
  summary["error"] = error;
  summary["exit_code"] = exit_code;
  try {
    io::write_json_file(dir + "/summary.json", summary);
  } catch (const std::exception&) {
    // (a full disk, or summary.json a folder: the marker stays and says the run did not end)
  }
}

RunFolder::~RunFolder() {
  remove_temporaries(dir_);
  // The manifest: this run's outputs (written since its marker) and the names it carries.
  std::set<std::string> names;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir_, ec)) {
    const std::string name = entry.path().filename().string();
    std::error_code e;
    if (!entry.is_regular_file(e) || !is_run_output(name) || ends_with(name, ".tmp")) continue;
    if (carried_.count(name) || (entry.last_write_time(e) >= start_ && !e)) names.insert(name);
  }
  const std::string file = dir_ + "/" + manifest, tmp = file + ".tmp";
  std::error_code ignored;
  if (names.empty()) {
    fs::remove(file, ignored);
  } else {
    bool written = false;
    if (!fs::exists(tmp, ignored)) {
      std::ofstream f(tmp, std::ios::trunc);
      f << "# the files a perinom run wrote in this folder: the next run here removes them (--keep keeps them),\n"
           "# and no other file\n";
      for (const auto& n : names) f << n << '\n';
      f.close();
      written = !f.fail();
    }
    std::error_code renamed;
    if (written) fs::rename(tmp, file, renamed);
    if (written) fs::remove(tmp, ignored);
    if (!written || renamed) {
      // A full disk left the manifest empty under its name and the marker gone: the next run
      // here refused this run's files as no run's. The marker stays instead, and its time
      // tells the next run which files are this run's.
      std::fprintf(stderr,
                   "perinom: warning: the list of this run's files (%s) could not be written (a full disk?); %s "
                   "stays, so that the next run here still knows them\n",
                   file.c_str(), marker);
      return;
    }
  }
  // A folder without its summary is not a finished run: the marker says so.
  if (!written_since(dir_, "summary.json", start_)) {
    std::fprintf(stderr, "perinom: warning: %s/summary.json could not be written; %s stays: the run did not end "
                 "with a summary\n", dir_.c_str(), marker);
    return;
  }
  fs::remove(dir_ + "/" + marker, ignored);
}

void RunFolder::announce() const {
  if (removed_ > 0)
    std::printf("perinom: removed %d files of an earlier run from %s (--keep keeps them)\n", removed_, dir_.c_str());
  if (foreign_.empty()) return;
  std::string list;
  const std::size_t shown = std::min<std::size_t>(foreign_.size(), 5);
  for (std::size_t k = 0; k < shown; ++k) list += (k ? ", " : "") + foreign_[k];
  if (foreign_.size() > shown) list += " and " + std::to_string(foreign_.size() - shown) + " more";
  warn("--out %s holds %zu file(s) named like perinom's output that no perinom run recorded "
              "writing there (%s): left in place, and not this run's",
              dir_.c_str(), foreign_.size(), list.c_str());
}

}  // namespace perinom::cli
