#include "output_folder.hpp"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <regex>

#include "perinom/core/error.hpp"

namespace perinom::cli {
namespace {

namespace fs = std::filesystem;

/// Removes the files is_run_output names (or only the .tmp ones); returns how many.
int remove_outputs(const std::string& dir, bool only_tmp) {
  int removed = 0;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    const bool tmp = name.size() > 4 && name.compare(name.size() - 4, 4, ".tmp") == 0;
    if (name == RunFolder::marker || !entry.is_regular_file(ec) || !is_run_output(name) || (only_tmp && !tmp))
      continue;
    std::error_code gone;
    if (fs::remove(entry.path(), gone)) ++removed;
  }
  return removed;
}

}  // namespace

bool is_run_output(const std::string& file_name) {
  static const std::regex names(
      R"((summary\.json|history\.csv|load_steps\.csv|.*\.vtu|.*\.pvd|probe_.*\.csv|.*_[0-9]{6,}\.csv)(\.tmp)?)");
  return std::regex_match(file_name, names);
}

RunFolder::RunFolder(std::string dir, bool keep) : dir_(std::move(dir)) {
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
  removed_ = remove_outputs(dir_, keep);
}

RunFolder::~RunFolder() {
  remove_outputs(dir_, true);
  std::error_code ignored;
  fs::remove(dir_ + "/" + marker, ignored);
}

}  // namespace perinom::cli
