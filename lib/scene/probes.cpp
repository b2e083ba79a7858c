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

}  // namespace perinom
