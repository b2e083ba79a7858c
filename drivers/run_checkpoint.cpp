#include "run_checkpoint.hpp"

#include <algorithm>
#include <fstream>
#include <iterator>

#include "perinom/core/error.hpp"
#include "perinom/scene/registry.hpp"

namespace perinom::cli {

RunIdentity run_identity(const Problem& p) { return {positions_fingerprint(p), body_files_fingerprint(p.scene)}; }

io::Checkpoint run_records(const Problem& p, const RunIdentity& id, const RunProgress& run) {
  io::Checkpoint c;
  c.put("scene", p.scene.canonical);
  c.put_integer("particles", static_cast<std::int64_t>(p.physics().particles()));
  c.put_integer("dofs", static_cast<std::int64_t>(p.physics().dofs()));
  c.put_integer("positions", static_cast<std::int64_t>(id.positions));
  c.put_integer("body_files", static_cast<std::int64_t>(id.body_files));
  c.put("solver", checkpoint_solver(p.scene));
  std::vector<double> times;
  std::string files;
  for (const auto& s : run.snapshots) times.push_back(s.time), files += s.file + "\n";
  c.put("snapshot_times", std::move(times));
  c.put("snapshot_files", std::move(files));
  std::vector<std::int64_t> csv = run.snapshot_csv;
  csv.resize(run.snapshots.size(), 0);
  c.put("snapshot_csv", std::move(csv));
  c.put_integer("last_snapshot", run.last_snapshot);
  std::vector<double> rows;
  for (const auto& row : run.probe_rows) rows.insert(rows.end(), row.begin(), row.end());
  c.put_integer("probe_columns", run.probe_rows.empty() ? 0 : static_cast<std::int64_t>(run.probe_rows[0].size()));
  c.put("probe_rows", std::move(rows));
  if (!run.stress_path.empty()) c.put("stress_path", run.stress_path);
  return c;
}

std::uint64_t positions_fingerprint(const Problem& p) {
  return io::fnv1a64(p.cloud.x.data(), p.cloud.x.size() * sizeof(double));
}

std::uint64_t body_files_fingerprint(const Scene& scene) {
  const BodyFiles& f = scene.body_files;
  if (!f.given()) return 0;
  std::string bytes;
  for (const std::string* path : {&f.mesh, &f.points, &f.facets}) {
    if (path->empty()) continue;
    std::ifstream in(*path, std::ios::binary);
    bytes += std::string(std::istreambuf_iterator<char>(in), {}) + '\0';
  }
  return io::fnv1a64(bytes.data(), bytes.size());
}

std::string checkpoint_solver(const Scene& scene) {
  return scene.load_path() ? "load_path" : solver_of(scene).checkpoint_state;
}

RunProgress run_progress(const io::Checkpoint& c) {
  RunProgress run;
  const auto& times = c.reals("snapshot_times");
  const std::string& files = c.text("snapshot_files");
  std::size_t at = 0;
  for (const double t : times) {
    const std::size_t end = files.find('\n', at);
    const std::string file = end == std::string::npos ? "" : files.substr(at, end - at);
    // Names the run wrote itself: no folder part, nothing to escape the output folder with.
    if (file.empty() || file.find('/') != std::string::npos || file[0] == '.')
      throw InputError(c.source + ": the checkpoint's snapshot_files do not match its snapshot_times");
    run.snapshots.push_back({t, file});
    at = end + 1;
  }
  if (at != files.size()) throw InputError(c.source + ": the checkpoint lists more snapshot_files than snapshot_times");
  if (c.has("snapshot_csv")) run.snapshot_csv = c.integers("snapshot_csv", times.size());
  run.last_snapshot = c.integer("last_snapshot");
  const std::int64_t columns = c.integer("probe_columns");
  const auto& rows = c.reals("probe_rows");
  if (columns < 0 || (columns == 0 && !rows.empty()) || (columns > 0 && rows.size() % std::size_t(columns)))
    throw InputError(c.source + ": the checkpoint's probe_rows do not fill rows of probe_columns");
  for (std::size_t k = 0; columns > 0 && k < rows.size(); k += std::size_t(columns))
    run.probe_rows.emplace_back(rows.begin() + k, rows.begin() + k + columns);
  if (c.has("stress_path")) run.stress_path = c.reals("stress_path", 2);
  return run;
}

}  // namespace perinom::cli
