#include "small_strain_check.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "perinom/distributed/ranks.hpp"
#include "diagnostics.hpp"

namespace perinom::cli {
namespace {

const OutputField* find_field(const std::vector<OutputField>& fields, const std::string& name) {
  for (const OutputField& f : fields)
    if (f.name == name) return &f;
  return nullptr;
}

}  // namespace

SmallStrainMeasure measure_small_strain(const Scene& scene, const Model& model, const double* u, std::size_t particles) {
  SmallStrainMeasure m;
  if (scene.model.kinematics != "small_strain") return m;
  const std::vector<OutputField> fields = model.output_fields(u, true);
  const OutputField* H = find_field(fields, "displacement_gradient");
  const OutputField* w = find_field(fields, "deflection");
  if (!H && !w) return m;
  m.kind = H ? SmallStrainMeasure::Kind::gradient : SmallStrainMeasure::Kind::deflection;
  const OutputField& f = H ? *H : *w;
  const OutputField* damage = H ? find_field(fields, "damage") : nullptr;
  const int c = f.components;
  for (std::size_t i = 0; i < particles; ++i) {
    if (damage && damage->values[i] > 0.0) continue;
    double s = 0.0;
    for (int k = 0; k < c; ++k) s += f.values[i * c + k] * f.values[i * c + k];
    if (std::sqrt(s) > m.value) m.value = std::sqrt(s), m.particle = i;
  }
  return m;
}

void report_small_strain(const Problem& p, const SmallStrainMeasure& m, io::Json& summary) {
  if (m.kind == SmallStrainMeasure::Kind::none) return;
  const int d = p.cloud.dim;
  io::Json j = io::Json::object(), x = io::Json::array();
  std::string where;
  char buf[48];
  for (int a = 0; a < d; ++a) {
    x.push_back(p.cloud.x[m.particle * d + a]);
    std::snprintf(buf, sizeof buf, "%s%g", a ? ", " : "", p.cloud.x[m.particle * d + a]);
    where += buf;
  }
  j["value"] = m.value;
  if (m.kind == SmallStrainMeasure::Kind::gradient) {
    j["particle"] = static_cast<long long>(m.particle);
    j["position"] = x;
    summary["largest_displacement_gradient"] = j;
    if (m.value > kSmallGradientLimit)
      warn("the displacement gradient |grad u| reaches %.3g at particle %zu at (%s) "
                  "(summary.json largest_displacement_gradient); beyond about %g strains and rotations are not small, "
                  "and a small-strain model's answer is not the body's: check the units of the moduli, loads and "
                  "lengths%s",
                  m.value, m.particle, where.c_str(), kSmallGradientLimit,
                  p.scene.plasticity ? " (model.kinematics: finite_rotation follows large rotations)" : "");
    return;
  }
  const double t = p.scene.geometry.thickness;
  j["over_thickness"] = m.value / t;
  j["particle"] = static_cast<long long>(m.particle);
  j["position"] = x;
  summary["largest_deflection"] = j;
  if (m.value > kSmallDeflectionLimit * t)
    warn("the deflection reaches %.3g m at node %zu at (%s), %.3g times the plate's thickness "
                "(summary.json largest_deflection); beyond about %g of it the plate stretches as it bends, which the "
                "linear plate does not model, and its answer is not the plate's: check the units of the moduli, "
                "loads and lengths",
                m.value, m.particle, where.c_str(), m.value / t, kSmallDeflectionLimit);
}

void check_small_strain(const Problem& p, const std::vector<double>& u, io::Json& summary) {
  report_small_strain(p, measure_small_strain(p.scene, p.physics(), u.data(), p.cloud.size()), summary);
}

void check_small_strain_over_ranks(const RankRun& run, const std::vector<double>& u, io::Json& summary) {
  SmallStrainMeasure m = measure_small_strain(run.frame.scene, run.model, u.data(), run.part.owned);
  if (m.kind == SmallStrainMeasure::Kind::none) return;  // alike on every rank: the scene decides
  const double largest = max_over_ranks(m.value);
  const double holder = -max_over_ranks(m.value == largest ? -double(run.rank) : -double(run.ranks));
  const bool mine = double(run.rank) == holder;
  const double particle = sum_over_ranks(mine && run.part.owned > 0 ? double(run.part.particles[m.particle]) : 0.0);
  m.value = largest;
  m.particle = static_cast<std::size_t>(particle);
  report_small_strain(run.frame, m, summary);
}

}  // namespace perinom::cli
