#include "refused_run.hpp"

#include "output_folder.hpp"

namespace perinom::cli {

void RefusedRun::record(const std::string& error, int exit_code) const {
  if (dir_.empty() || !RunFolder::holds_run(dir_)) return;
  try {
    const RunFolder folder(dir_, keep_);
    folder.announce();
    folder.record_error(scene_file_, name_, error, exit_code);
  } catch (const std::exception&) {
    // The folder cannot be prepared (another run writing it, a file of the user's): it is
    // left as it is, and the refusal said on its own.
  }
}

}  // namespace perinom::cli
