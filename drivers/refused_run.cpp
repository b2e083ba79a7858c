#include "refused_run.hpp"

#include <filesystem>

#include "output_folder.hpp"

namespace perinom::cli {

void RefusedRun::folder(const std::string& dir, std::string name) {
  std::error_code e;
  const bool resumed = !restart_.empty() && std::filesystem::equivalent(restart_, dir, e);
  dir_ = resumed ? "" : dir, name_ = std::move(name);
}

void RefusedRun::record(const std::string& error, int exit_code) const {
  if (!dir_.empty() && RunFolder::holds_finished_run(dir_))
    RunFolder::write_error_summary(dir_, scene_file_, name_, error, exit_code);
}

}  // namespace perinom::cli
