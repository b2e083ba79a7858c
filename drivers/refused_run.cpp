#include "refused_run.hpp"

#include "output_folder.hpp"

namespace perinom::cli {

void RefusedRun::record(const std::string& error, int exit_code) const {
  if (!dir_.empty() && RunFolder::holds_finished_run(dir_))
    RunFolder::write_error_summary(dir_, scene_file_, name_, error, exit_code);
}

}  // namespace perinom::cli
