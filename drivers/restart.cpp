#include "restart.hpp"

#include <cstdio>
#include <filesystem>
#include <utility>

#include "perinom/core/error.hpp"
#include "perinom/scene/scene_difference.hpp"

namespace perinom::cli {
namespace {

namespace fs = std::filesystem;

std::string describe(const SceneDifference& d, const Scene& scene) {
  const std::string values =
      d.first + " in the checkpoint and " + d.second + " in " + scene.source + " as run (--set included)";
  return d.key.empty() ? values : d.key + " is " + values;
}

/// Where the checkpoint's solver stood: "iteration N", "step N (t = T s)", "load step S of stage K".
std::string position(const io::Checkpoint& c) {
  const std::string solver = c.text("solver");
  if (solver == "adr") return "iteration " + std::to_string(c.integer("adr.iterations"));
  if (solver == "verlet") {
    char t[32];
    std::snprintf(t, sizeof t, "%.6e", c.real("verlet.time"));
    return "step " + std::to_string(c.integer("verlet.step")) + ", t = " + t + " s";
  }
  return "load step " + std::to_string(c.integer("load_path.step")) + " of stage " +
         std::to_string(c.integer("load_path.stage") + 1);
}

}  // namespace

Restart::Restart(std::string dir, const Scene& scene) : dir_(std::move(dir)) {
  const std::string at = "--restart " + dir_ + ": ";
  if (scene.solver.type == "newton")
    throw InputError(at + "Newton solves are not checkpointed, so not resumed (adr, verlet and lbc solves are)");
  std::error_code ec;
  if (!fs::is_directory(dir_, ec))
    throw InputError(at + (fs::exists(dir_, ec) ? "not a folder (give the output folder of the run)" : "no such folder"));
  const std::string path = dir_ + "/" + checkpoint_name;
  if (!fs::exists(path, ec))
    throw InputError(at + "the folder holds no checkpoint (" + checkpoint_name +
                     "; a run writes one when output.checkpoint_every is set)");
  try {
    file_ = io::read_checkpoint(path);
    if (const auto d = scene_difference(file_.text("scene"), scene.canonical))
      throw InputError("the checkpoint was written for another scene: " + describe(*d, scene));
    const std::string solver = file_.text("solver"), wanted = checkpoint_solver(scene);
    if (solver != wanted)
      throw InputError("the checkpoint holds the state of a " + solver + " solve, the scene runs " + wanted);
    progress_ = run_progress(file_);
    where_ = path + " (" + position(file_) + ")";
  } catch (const InputError& e) {
    throw InputError(at + e.what());
  }
}

bool Restart::in_place(const std::string& out) const {
  std::error_code ec;
  return fs::equivalent(dir_, out, ec);  // false while out does not exist
}

std::set<std::string> Restart::files() const {
  std::set<std::string> out = {checkpoint_name};
  for (std::size_t k = 0; k < progress_.snapshots.size(); ++k) {
    const auto& s = progress_.snapshots[k];
    if (!fs::is_regular_file(dir_ + "/" + s.file))
      throw InputError("--restart " + dir_ + ": the checkpoint lists the snapshot " + s.file +
                       ", which the folder does not hold");
    out.insert(s.file);
    // Its .csv where the checkpoint saw one, or where one is there (a checkpoint from before
    // snapshot_csv was recorded): a resumed run without it ended with exit 0 and a folder
    // short of the files the user asked for.
    const std::string csv = s.file.substr(0, s.file.rfind('.')) + ".csv";
    const bool there = fs::is_regular_file(dir_ + "/" + csv);
    if (k < progress_.snapshot_csv.size() && progress_.snapshot_csv[k] != 0 && !there)
      throw InputError("--restart " + dir_ + ": the checkpoint lists the snapshot " + s.file +
                       ", whose point data the run also wrote as " + csv + " (output.csv), which the folder does not hold");
    if (there) out.insert(csv);
  }
  return out;
}

void Restart::bring_snapshots(const std::string& out) const {
  if (in_place(out)) return;
  for (const auto& file : files()) {
    // As every file of a run: under its name only when whole.
    const std::string to = out + "/" + file, tmp = to + ".tmp";
    std::error_code ec;
    fs::copy_file(dir_ + "/" + file, tmp, fs::copy_options::overwrite_existing, ec);
    if (!ec) fs::rename(tmp, to, ec);
    if (ec) {
      std::error_code ignored;
      fs::remove(tmp, ignored);
      throw InputError("--restart " + dir_ + ": copying " + file + " into " + out + " failed: " + ec.message());
    }
  }
}

namespace {

/// "geometry.points cloud.csv, geometry.facets f.csv" for the message.
std::string files_named(const Scene& s) {
  std::string out;
  for (const auto& [key, path] : {std::pair<const char*, const std::string*>{"geometry.mesh", &s.body_files.mesh},
                                  {"geometry.points", &s.body_files.points}, {"geometry.facets", &s.body_files.facets}})
    if (!path->empty()) out += (out.empty() ? "" : ", ") + std::string(key) + " " + *path;
  return out;
}

}  // namespace

void Restart::check(const Problem& p) const {
  const std::int64_t particles = file_.integer("particles"), dofs = file_.integer("dofs");
  if (particles != std::int64_t(p.physics().particles()) || dofs != std::int64_t(p.physics().dofs()))
    throw InputError("--restart " + dir_ + ": the checkpoint holds " + std::to_string(particles) + " particles and " +
                     std::to_string(dofs) + " degrees of freedom, the scene builds " +
                     std::to_string(p.physics().particles()) + " and " + std::to_string(p.physics().dofs()) +
                     " (has a mesh or point file changed?)");
  if (static_cast<std::uint64_t>(file_.integer("positions")) != positions_fingerprint(p))
    throw InputError("--restart " + dir_ + ": the checkpoint's particles are not where the scene places them "
                     "(has a mesh or point file changed?)");
  // (Checkpoints written before 2026-12-07 do not have it.)
  if (file_.has("body_files") && static_cast<std::uint64_t>(file_.integer("body_files")) != body_files_fingerprint(p.scene))
    // What is compared is the files' bytes: a file only reformatted (", " for ",") differs
    // too, and was said to have changed its volumes, facets or groups.
    throw InputError("--restart " + dir_ + ": the text of the body's files (" + files_named(p.scene) +
                     ") is not, byte for byte, that of the files the checkpoint was written from (the particles are "
                     "where it placed them; a volume, facet or group changed, or only the text was rewritten): restore "
                     "the files, or run from the start");
}

}  // namespace perinom::cli
