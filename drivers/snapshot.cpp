#include "snapshot.hpp"

#include <cmath>

#include "perinom/core/error.hpp"
#include "perinom/io/csv_writer.hpp"
#include "plate_output.hpp"

namespace perinom::cli {

namespace {

/// The scalar and vector fields of a snapshot as CSV: x, y, z, then each field's components.
void write_csv(const std::string& path, const Problem& p, const std::vector<io::PointField>& fields) {
  std::vector<std::string> names = {"x", "y", "z"};
  for (const auto& f : fields)
    for (int c = 0; c < f.components; ++c)
      names.push_back(f.components == 1 ? f.name : f.name + "_" + std::to_string(c));
  io::CsvWriter csv(path);
  csv.header(names);
  const int d = p.cloud.dim;
  std::vector<double> row;
  for (std::size_t i = 0; i < p.cloud.size(); ++i) {
    row.assign(3, 0.0);
    for (int a = 0; a < d; ++a) row[a] = p.cloud.x[i * d + a];
    for (const auto& f : fields) row.insert(row.end(), f.data + i * f.components, f.data + (i + 1) * f.components);
    csv.row(row);
  }
  csv.close();
}

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
  const int d = p.cloud.dim;
  if (p.plate) {
    const PlateFields plate(p, u);
    const std::vector<io::PointField> fields = plate.list(p, u);
    require_finite(fields, p.cloud.size());
    const std::string file = series.add(time, d, p.cloud.size(), p.cloud.x.data(), fields);
    series.write();
    if (p.scene.output.csv && !dir.empty()) write_csv(dir + "/" + file.substr(0, file.size() - 4) + ".csv", p, fields);
    return;
  }
  const std::size_t n = p.cloud.size();
  std::vector<double> u3(n * 3, 0.0), sigma, vm(n), mean(n);
  for (std::size_t i = 0; i < n; ++i)
    for (int a = 0; a < d; ++a) u3[i * 3 + a] = u[i * d + a];
  p.model->stress3(u.data(), sigma);
  for (std::size_t i = 0; i < n; ++i) {
    vm[i] = von_mises(sigma.data() + i * 9);
    mean[i] = mean_stress(sigma.data() + i * 9);
  }
  std::vector<io::PointField> fields = {{"displacement", 3, u3.data()}, {"stress", 9, sigma.data()},
                                        {"von_mises", 1, vm.data()},    {"mean_stress", 1, mean.data()},
                                        {"volume", 1, p.cloud.volume.data()}};
  // The stress at the surface: each facet owner's stress reconstructed at its facets'
  // centroids, area-weighted (the facets of a corner particle: their mean); elsewhere the
  // particle's own stress (finite: the snapshot guard refuses NaN, and a user's colour map
  // then shows the whole body).
  std::vector<double> surface_sigma, surface_vm;
  const BoundaryFacets& facets = p.model->trace().facets();
  if (!facets.empty()) {
    const std::vector<double> grad_sigma = stress_gradient(*p.model, sigma);
    std::vector<double> area(n, 0.0);
    surface_sigma.assign(n * 9, 0.0);
    double s9[9];
    for (std::size_t k = 0; k < facets.size(); ++k) {
      const std::size_t i = facets.particle[k];
      reconstruct_stress(sigma, grad_sigma, p.cloud, i, facets.centroid.data() + k * d, s9);
      for (int c = 0; c < 9; ++c) surface_sigma[i * 9 + c] += facets.area[k] * s9[c];
      area[i] += facets.area[k];
    }
    surface_vm.assign(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      for (int c = 0; c < 9; ++c)
        surface_sigma[i * 9 + c] = area[i] > 0.0 ? surface_sigma[i * 9 + c] / area[i] : sigma[i * 9 + c];
      surface_vm[i] = von_mises(surface_sigma.data() + i * 9);
    }
    fields.push_back({"surface_stress", 9, surface_sigma.data()});
    fields.push_back({"surface_von_mises", 1, surface_vm.data()});
  }
  // Improved and strong formulations: subregion 1 = E (strong form), 0 = D (weak form).
  std::vector<double> subregion, surface;
  const Surface& s = p.model->surface();
  if (!s.in_band.empty()) {
    subregion.assign(s.in_band.begin(), s.in_band.end());
    surface.assign(s.on_surface.begin(), s.on_surface.end());
    fields.push_back({"subregion_E", 1, subregion.data()});
    fields.push_back({"surface", 1, surface.data()});
  }
  std::vector<double> xi, eps_p, yielded;
  if (const PlasticPoints* plastic = p.model->plastic()) {
    for (const auto& point : plastic->committed()) {
      xi.push_back(point.law.xi);
      yielded.push_back(point.law.xi > 0.0 ? 1.0 : 0.0);
      eps_p.insert(eps_p.end(), point.law.eps_p, point.law.eps_p + 9);
    }
    fields.push_back({"eq_plastic_strain", 1, xi.data()});
    fields.push_back({"plastic_strain", 9, eps_p.data()});
    fields.push_back({"yielded", 1, yielded.data()});
  }
  require_finite(fields, n);
  const std::string file = series.add(time, d, n, p.cloud.x.data(), fields);
  series.write();
  if (p.scene.output.csv && !dir.empty())
    write_csv(dir + "/" + file.substr(0, file.size() - 4) + ".csv", p, fields);
}

ProbeState::ProbeState(const Problem& p, const std::vector<double>& u)
    : H(p.cloud.size() * p.cloud.dim * p.cloud.dim) {
  p.model->stress3(u.data(), sigma);
  p.model->gradient(u.data(), H.data());
  for (const auto& probe : p.probes)
    if (!probe.spec.is_line && probe.spec.reconstruct && stress_field(probe.spec.field)) {
      grad_sigma = stress_gradient(*p.model, sigma);
      break;
    }
}

}  // namespace perinom::cli
