#include "small_strain_check.hpp"

#include <cmath>
#include <cstdio>
#include <string>

namespace perinom::cli {
namespace {

const OutputField* find_field(const std::vector<OutputField>& fields, const std::string& name) {
  for (const OutputField& f : fields)
    if (f.name == name) return &f;
  return nullptr;
}

io::Json place(const Problem& p, std::size_t i, std::string& text) {
  const int d = p.cloud.dim;
  io::Json x = io::Json::array();
  char buf[48];
  for (int a = 0; a < d; ++a) {
    x.push_back(p.cloud.x[i * d + a]);
    std::snprintf(buf, sizeof buf, "%s%g", a ? ", " : "", p.cloud.x[i * d + a]);
    text += buf;
  }
  return x;
}

/// A thin plate's largest |w| against its thickness.
void check_plate(const Problem& p, const OutputField& w, io::Json& summary) {
  double largest = 0.0;
  std::size_t at = 0;
  for (std::size_t i = 0; i < w.values.size(); ++i)
    if (std::abs(w.values[i]) > largest) largest = std::abs(w.values[i]), at = i;
  const double t = p.scene.geometry.thickness;
  std::string where;
  io::Json j = io::Json::object();
  j["value"] = largest;
  j["over_thickness"] = largest / t;
  j["particle"] = static_cast<long long>(at);
  j["position"] = place(p, at, where);
  summary["largest_deflection"] = j;
  if (largest > kSmallDeflectionLimit * t)
    std::printf("perinom: warning: the deflection reaches %.3g m at node %zu at (%s), %.3g times the plate's thickness "
                "(summary.json largest_deflection); beyond about %g of it the plate stretches as it bends, which the "
                "linear plate does not model, and its answer is not the plate's: check the units of the moduli, "
                "loads and lengths\n",
                largest, at, where.c_str(), largest / t, kSmallDeflectionLimit);
}

}  // namespace

void check_small_strain(const Problem& p, const std::vector<double>& u, io::Json& summary) {
  if (p.scene.model.kinematics != "small_strain") return;
  const std::vector<OutputField> fields = p.physics().output_fields(u.data(), true);
  const OutputField* H = find_field(fields, "displacement_gradient");
  if (!H) {
    if (const OutputField* w = find_field(fields, "deflection")) check_plate(p, *w, summary);
    return;
  }
  const OutputField* damage = find_field(fields, "damage");
  const int dd = H->components;
  double largest = 0.0;
  std::size_t at = 0;
  for (std::size_t i = 0; i < p.cloud.size(); ++i) {
    if (damage && damage->values[i] > 0.0) continue;
    double s = 0.0;
    for (int c = 0; c < dd; ++c) s += H->values[i * dd + c] * H->values[i * dd + c];
    if (std::sqrt(s) > largest) largest = std::sqrt(s), at = i;
  }
  std::string where;
  io::Json j = io::Json::object();
  j["value"] = largest;
  j["particle"] = static_cast<long long>(at);
  j["position"] = place(p, at, where);
  summary["largest_displacement_gradient"] = j;
  if (largest > kSmallGradientLimit)
    std::printf("perinom: warning: the displacement gradient |grad u| reaches %.3g at particle %zu at (%s) "
                "(summary.json largest_displacement_gradient); beyond about %g strains and rotations are not small, "
                "and a small-strain model's answer is not the body's: check the units of the moduli, loads and "
                "lengths\n",
                largest, at, where.c_str(), kSmallGradientLimit);
}

}  // namespace perinom::cli
