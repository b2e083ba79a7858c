// Probes read from any model's output fields (ProbeReadout): the drivers never ask which
// model they have.
#include <cmath>

#include "perinom/scene/problem.hpp"

namespace perinom {
namespace {

bool needs_gradients(const Problem& p) {
  for (const auto& probe : p.probes)
    if (!probe.spec.is_line && probe.spec.reconstruct && stress_field(probe.spec.field)) return true;
  return false;
}

const std::vector<double>* values_of(const std::vector<OutputField>& fields, const std::string& name) {
  for (const auto& f : fields)
    if (f.name == name) return &f.values;
  return nullptr;
}

}  // namespace

ProbeReadout::ProbeReadout(const Problem& p, const std::vector<double>& u)
    : p_(p),
      u_(u),
      fields_(p.physics().output_fields(u.data(), true, needs_gradients(p))),
      view_{p.cloud,
            u,
            values_of(fields_, "stress") ? *values_of(fields_, "stress") : none_,
            values_of(fields_, "displacement_gradient") ? *values_of(fields_, "displacement_gradient") : none_,
            values_of(fields_, "stress_gradient"),
            values_of(fields_, "eq_plastic_strain"),
            &fields_} {}

const OutputField* ProbeReadout::find(const std::string& name) const {
  for (const auto& f : fields_)
    if (f.name == name) return &f;
  return nullptr;
}

double ProbeReadout::scalar(const std::string& name, std::size_t i) const {
  const OutputField* f = find(name);
  return f ? f->values[i * f->components] : 0.0;
}

double ProbeReadout::point(const BoundProbe& probe) const { return point_probe_value(probe, view_); }

double ProbeReadout::at(const ProbeSpec& spec, std::size_t i) const { return probe_value(spec, i, view_); }

std::vector<std::string> ProbeReadout::line_header(const ProbeSpec& spec) const {
  if (find("von_mises")) return {"s", "x", "y", "z", "ux", "uy", "uz", "von_mises", "value"};
  return {"s", "x", "y", "z", spec.field};
}

std::vector<double> ProbeReadout::line_row(const BoundProbe& probe, std::size_t k) const {
  const int d = p_.cloud.dim;
  const std::size_t i = probe.particles[k];
  const bool solid = find("von_mises") != nullptr;
  std::vector<double> row(solid ? 9 : 5, 0.0);
  row[0] = probe.along[k];
  for (int a = 0; a < d; ++a) row[1 + a] = p_.cloud.x[i * d + a];
  if (!solid) {
    row[4] = at(probe.spec, i);
    return row;
  }
  for (int a = 0; a < d; ++a) row[4 + a] = u_[i * d + a];
  row[7] = scalar("von_mises", i);
  row[8] = at(probe.spec, i);
  return row;
}

namespace {
int axis_of(char c) { return c == 'x' ? 0 : c == 'y' ? 1 : 2; }
}  // namespace

bool stress_field(const std::string& field) {
  return field == "stress" || field == "von_mises" || field == "mean_stress";
}

std::vector<double> stress_gradient(const CorrespondenceModel& model, const std::vector<double>& sigma) {
  std::vector<double> out(sigma.size() * model.G().dim());
  model.G().apply(sigma.data(), 9, out.data());
  return out;
}

void reconstruct_stress(const std::vector<double>& sigma, const std::vector<double>& grad_sigma,
                        const PointCloud& cloud, std::size_t i, const double* y, double* out) {
  const int d = cloud.dim;
  for (int c = 0; c < 9; ++c) {
    out[c] = sigma[i * 9 + c];
    for (int b = 0; b < d; ++b) out[c] += grad_sigma[(i * 9 + c) * d + b] * (y[b] - cloud.x[i * d + b]);
  }
}

double stress_probe_value(const ProbeSpec& spec, const double* sigma3) {
  if (spec.field == "stress") return sigma3[axis_of(spec.component[0]) * 3 + axis_of(spec.component[1])];
  if (spec.field == "mean_stress") return mean_stress(sigma3);
  return von_mises(sigma3);
}

double probe_value(const ProbeSpec& spec, std::size_t i, const ProbeFields& f) {
  const int d = f.cloud.dim;
  if (spec.field == "displacement") return f.u[i * d + axis_of(spec.component[0])];
  if (stress_field(spec.field)) return stress_probe_value(spec, f.sigma.data() + i * 9);
  if (spec.field == "eq_plastic_strain")
    return f.eq_plastic_strain ? (*f.eq_plastic_strain)[i] : 0.0;
  if (f.fields)
    for (const auto& field : *f.fields)
      if (field.name == spec.field) return field.values[i * field.components];
  throw std::logic_error("probe_value: unknown field " + spec.field);
}

double point_probe_value(const BoundProbe& probe, const ProbeFields& f) {
  const std::size_t i = probe.particles.at(0);
  if (probe.spec.reconstruct && stress_field(probe.spec.field)) {
    if (!f.grad_sigma) throw std::logic_error("point_probe_value: a reconstructed stress probe needs grad sigma");
    double s[9];
    reconstruct_stress(f.sigma, *f.grad_sigma, f.cloud, i, probe.spec.point.data(), s);
    return stress_probe_value(probe.spec, s);
  }
  double v = probe_value(probe.spec, i, f);
  if (!probe.spec.reconstruct) return v;
  const int d = f.cloud.dim, a = axis_of(probe.spec.component[0]);
  for (int b = 0; b < d; ++b) v += f.H[(i * d + a) * d + b] * (probe.spec.point[b] - f.cloud.x[i * d + b]);
  return v;
}

}  // namespace perinom
