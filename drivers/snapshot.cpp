#include "snapshot.hpp"

#include <cmath>

#include "perinom/core/error.hpp"
#include "perinom/io/csv_writer.hpp"

namespace perinom::cli {

void write_snapshot_csv(const std::string& path, const PointCloud& cloud, const std::vector<io::PointField>& fields) {
  std::vector<std::string> names = {"x", "y", "z"};
  for (const auto& f : fields)
    for (int c = 0; c < f.components; ++c)
      names.push_back(f.components == 1 ? f.name : f.name + "_" + std::to_string(c));
  io::CsvWriter csv(path);
  csv.header(names);
  const int d = cloud.dim;
  std::vector<double> row;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    row.assign(3, 0.0);
    for (int a = 0; a < d; ++a) row[a] = cloud.x[i * d + a];
    for (const auto& f : fields) row.insert(row.end(), f.data + i * f.components, f.data + (i + 1) * f.components);
    csv.row(row);
  }
  csv.close();
}

namespace {

/// The guard of every snapshot: no NaN or Inf reaches a file.
void require_finite(const std::vector<io::PointField>& fields, std::size_t n) {
  for (const auto& f : fields)
    for (std::size_t k = 0; k < n * f.components; ++k)
      if (!std::isfinite(f.data[k]))
        throw SolveError("the snapshot's field '" + f.name + "' is NaN or Inf at particle " +
                         std::to_string(k / f.components));
}

}  // namespace

void add_snapshot(io::PvdSeries& series, double time, const Problem& p, const std::vector<double>& u,
                  const std::string& dir) {
  const std::vector<OutputField> model_fields = p.physics().output_fields(u.data());
  std::vector<io::PointField> fields;
  for (const auto& f : model_fields) fields.push_back({f.name, f.components, f.values.data()});
  const std::size_t n = p.cloud.size();
  require_finite(fields, n);
  const std::string file = series.add(time, p.cloud.dim, n, p.cloud.x.data(), fields);
  series.write();
  if (p.scene.output.csv && !dir.empty())
    write_snapshot_csv(dir + "/" + file.substr(0, file.size() - 4) + ".csv", p.cloud, fields);
}

}  // namespace perinom::cli
