#include "output_folder.hpp"

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "perinom/core/error.hpp"

namespace perinom::cli {
namespace {

namespace fs = std::filesystem;

/// Removes the files is_run_output names (or only the .tmp ones) but those in `spare`;
/// returns how many.
int remove_outputs(const std::string& dir, bool only_tmp, const std::set<std::string>& spare = {}) {
  int removed = 0;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    const bool tmp = name.size() > 4 && name.compare(name.size() - 4, 4, ".tmp") == 0;
    if (name == RunFolder::marker || !entry.is_regular_file(ec) || !is_run_output(name) || (only_tmp && !tmp) ||
        spare.count(name))
      continue;
    std::error_code gone;
    if (fs::remove(entry.path(), gone)) ++removed;
  }
  return removed;
}

}  // namespace

bool is_run_output(const std::string& file_name) {
  const auto ends = [](const std::string& s, const std::string& end) {
    return s.size() >= end.size() && s.compare(s.size() - end.size(), end.size(), end) == 0;
  };
  std::string name = file_name;
  if (ends(name, ".tmp")) name.resize(name.size() - 4);
  if (name == "summary.json" || name == "history.csv" || name == "load_steps.csv" || name == "checkpoint.bin") return true;
  if (ends(name, ".vtu") || ends(name, ".pvtu") || ends(name, ".pvd")) return true;
  if (!ends(name, ".csv")) return false;
  if (name.rfind("probe_", 0) == 0) return true;
  // A snapshot's CSV: NAME_ and at least six digits (the .vtu's index).
  const std::string stem = name.substr(0, name.size() - 4);
  const std::size_t underscore = stem.rfind('_');
  return underscore != std::string::npos && stem.size() - underscore - 1 >= 6 &&
         stem.find_first_not_of("0123456789", underscore + 1) == std::string::npos;
}

RunFolder::RunFolder(std::string dir, bool keep, const std::set<std::string>& spare) : dir_(std::move(dir)) {
  std::error_code ec;
  fs::create_directories(dir_, ec);
  const std::string path = dir_ + "/" + marker;
  {
    std::ofstream f(path, std::ios::trunc);
    f << "perinom run in progress (process " << ::getpid()
      << "); if no perinom is running, the run that wrote this folder was killed\n";
    if (ec || !f.flush())
      throw InputError("--out " + dir_ + ": the output folder cannot be created or written");
  }
  removed_ = remove_outputs(dir_, keep, spare);
}

RunFolder::~RunFolder() {
  remove_outputs(dir_, true);
  std::error_code ignored;
  fs::remove(dir_ + "/" + marker, ignored);
}

}  // namespace perinom::cli
