#include "plate_output.hpp"

#include <cstdio>

#include "perinom/io/csv_writer.hpp"

namespace perinom::cli {
namespace {

/// (xx, xy, yy) per node into row-major 3 x 3 tensors.
std::vector<double> tensor9(const std::vector<double>& t3) {
  const std::size_t n = t3.size() / 3;
  std::vector<double> t(n * 9, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    t[i * 9 + 0] = t3[i * 3];
    t[i * 9 + 1] = t[i * 9 + 3] = t3[i * 3 + 1];
    t[i * 9 + 4] = t3[i * 3 + 2];
  }
  return t;
}

}  // namespace

PlateFields::PlateFields(const Problem& p, const std::vector<double>& w) : w3(w.size() * 3, 0.0) {
  const std::size_t n = w.size();
  for (std::size_t i = 0; i < n; ++i) w3[i * 3 + 2] = w[i];
  std::vector<double> t3(n * 3);
  p.plate->curvature(w.data(), t3.data());
  kappa9 = tensor9(t3);
  p.plate->moments(w.data(), t3.data());
  moment9 = tensor9(t3);
}

std::vector<io::PointField> PlateFields::list(const Problem& p, const std::vector<double>& w) const {
  return {{"deflection", 1, w.data()},
          {"displacement", 3, w3.data()},
          {"curvature", 9, kappa9.data()},
          {"moment", 9, moment9.data()},
          {"volume", 1, p.cloud.volume.data()}};
}

io::Json plate_probe_results(const Problem& p, const std::vector<double>& w, const std::string& dir) {
  io::Json out = io::Json::object();
  for (const auto& probe : p.probes) {
    if (!probe.spec.is_line) {
      const double v = w[probe.particles.at(0)];
      out[probe.spec.name] = v;
      std::printf("  %s = %.6e\n", probe.spec.name.c_str(), v);
      continue;
    }
    const std::string file = "probe_" + probe.spec.name + ".csv";
    io::CsvWriter csv(dir + "/" + file);
    csv.header({"s", "x", "y", "z", "deflection"});
    for (std::size_t k = 0; k < probe.particles.size(); ++k) {
      const std::size_t i = probe.particles[k];
      csv.row({probe.along[k], p.cloud.x[i * 2], p.cloud.x[i * 2 + 1], 0.0, w[i]});
    }
    csv.close();
    io::Json j = io::Json::object();
    j["file"] = file;
    j["points"] = probe.particles.size();
    out[probe.spec.name] = j;
  }
  return out;
}

}  // namespace perinom::cli
