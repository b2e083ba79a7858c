#include "distributed_output.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "perinom/core/error.hpp"
#include "perinom/io/csv_writer.hpp"
#include "snapshot.hpp"

namespace perinom::cli {
namespace {

/// Stops every rank alike when any has a non-finite value (`what` says where, on the rank
/// that saw it).
void require_finite_everywhere(bool finite, const std::string& what) {
  const double bad = max_over_ranks(finite ? 0.0 : 1.0);
  if (bad > 0.0) throw SolveError(finite ? "a value is NaN or Inf on another rank" : what);
}

/// output.csv: the snapshot's fields as one CSV in the whole cloud's order, as a serial run
/// writes it: every rank's owned rows (the particle's index in the whole cloud, then the
/// values) gathered on rank 0, which writes them.
void write_gathered_csv(const std::string& path, const RankRun& run, const std::vector<io::PointField>& fields) {
  std::size_t width = 1;
  for (const auto& f : fields) width += std::size_t(f.components);
  const std::size_t n = run.part.owned;
  std::vector<double> mine;
  mine.reserve(n * width);
  for (std::size_t p = 0; p < n; ++p) {
    mine.push_back(double(run.part.particles[p]));
    for (const auto& f : fields) mine.insert(mine.end(), f.data + p * f.components, f.data + (p + 1) * f.components);
  }
  const std::vector<double> all = gather_on_root(mine);
  if (run.rank != 0) return;
  const PointCloud& cloud = run.frame.cloud;
  if (all.size() != cloud.size() * width) throw std::logic_error("write_gathered_csv: the ranks' rows do not cover the cloud");
  std::vector<std::vector<double>> whole(fields.size());
  for (std::size_t k = 0; k < fields.size(); ++k) whole[k].resize(cloud.size() * std::size_t(fields[k].components));
  for (std::size_t r = 0; r < cloud.size(); ++r) {
    const double* row = all.data() + r * width;
    const auto i = std::size_t(row[0]);
    std::size_t at = 1;
    for (std::size_t k = 0; k < fields.size(); ++k)
      for (int c = 0; c < fields[k].components; ++c) whole[k][i * std::size_t(fields[k].components) + std::size_t(c)] = row[at++];
  }
  std::vector<io::PointField> in_order;
  for (std::size_t k = 0; k < fields.size(); ++k) in_order.push_back({fields[k].name, fields[k].components, whole[k].data()});
  write_snapshot_csv(path, cloud, in_order);
}

}  // namespace

void add_piece_snapshot(io::PvdSeries& series, double time, const RankRun& run, const std::vector<double>& u,
                        const std::string& dir) {
  const std::vector<OutputField> model_fields = run.model.output_fields(u.data());
  std::vector<io::PointField> fields;
  std::string bad;
  const std::size_t n = run.part.owned;
  for (const auto& f : model_fields) {
    fields.push_back({f.name, f.components, f.values.data()});
    for (std::size_t k = 0; k < f.values.size() && bad.empty(); ++k)
      if (!std::isfinite(f.values[k]))
        bad = "the snapshot's field '" + f.name + "' is NaN or Inf at particle " +
              std::to_string(run.part.particles[k / f.components]);
  }
  require_finite_everywhere(bad.empty(), bad);
  const std::string base = series.file_name("");
  std::vector<std::string> pieces;
  for (int r = 0; r < run.ranks; ++r) pieces.push_back(base + "_" + std::to_string(r) + ".vtu");
  io::write_vtu(dir + "/" + pieces[std::size_t(run.rank)], run.local.cloud.dim, n, run.local.cloud.x.data(), fields);
  barrier();  // every piece is there before the list that names them
  series.record(time, base + ".pvtu");
  if (run.rank == 0) {
    io::write_pvtu(dir + "/" + base + ".pvtu", pieces, fields);
    series.write();
  }
  if (run.frame.scene.output.csv) write_gathered_csv(dir + "/" + base + ".csv", run, fields);
}

io::Json distributed_probe_results(const RankRun& run, const std::vector<double>& u, const std::string& dir) {
  const auto at = owned_index(run.part);
  const std::vector<double>& state = run.model.local_state(u.data());
  const ProbeReadout readout(run.local, state);
  io::Json out = io::Json::object();
  for (const BoundProbe& probe : run.frame.probes) {
    // The probe's particles here: local indices where owned (the readout reads the local problem).
    BoundProbe mine = probe;
    std::vector<bool> owned(probe.particles.size(), false);
    for (std::size_t k = 0; k < probe.particles.size(); ++k) {
      const auto it = at.find(probe.particles[k]);
      if (it != at.end()) mine.particles[k] = ParticleId(it->second), owned[k] = true;
    }
    if (!probe.spec.is_line) {
      double v = owned[0] ? readout.point(mine) : 0.0;
      v = sum_over_ranks(v);
      require_finite_everywhere(std::isfinite(v), "probe '" + probe.spec.name + "': its value is NaN or Inf");
      out[probe.spec.name] = v;
      std::printf("  %s = %.6e\n", probe.spec.name.c_str(), v);
      continue;
    }
    const std::vector<std::string> header = readout.line_header(probe.spec);
    const std::size_t width = header.size();
    std::vector<double> rows(probe.particles.size() * width, 0.0);
    for (std::size_t k = 0; k < probe.particles.size(); ++k)
      if (owned[k]) {
        const std::vector<double> row = readout.line_row(mine, k);
        std::copy(row.begin(), row.end(), rows.begin() + std::ptrdiff_t(k * width));
      }
    sum_over_ranks(rows.data(), int(rows.size()));
    bool finite = true;
    for (const double x : rows) finite = finite && std::isfinite(x);
    require_finite_everywhere(finite, "probe '" + probe.spec.name + "': a value is NaN or Inf");
    const std::string file = "probe_" + probe.spec.name + ".csv";
    if (run.rank == 0) {
      io::CsvWriter csv(dir + "/" + file);
      csv.header(header);
      for (std::size_t k = 0; k < probe.particles.size(); ++k)
        csv.row(std::vector<double>(rows.begin() + std::ptrdiff_t(k * width), rows.begin() + std::ptrdiff_t((k + 1) * width)));
      csv.close();
    }
    io::Json j = io::Json::object();
    j["file"] = file;
    j["points"] = probe.particles.size();
    out[probe.spec.name] = j;
  }
  return out;
}

}  // namespace perinom::cli
