// The one model slot: what the drivers read of a model through Model alone (output fields,
// stress measure, plan lines, probes) is what the concrete models compute, for the
// correspondence model and the thin plate.
#include <catch2/catch.hpp>

#include <cmath>

#include "perinom/scene/problem.hpp"
#include "../support/pulled_bar.hpp"

using namespace perinom;

namespace {

const OutputField& field(const std::vector<OutputField>& fields, const std::string& name) {
  for (const auto& f : fields)
    if (f.name == name) return f;
  FAIL("no field " << name);
  return fields.front();
}

std::string plan_text(const Model& m, const std::string& label) {
  for (const auto& line : m.plan())
    if (line.label == label) return line.text;
  return "";
}

/// A deformed state: u = a x + b y^2 componentwise (for the plate, w alone).
std::vector<double> state(const Problem& p) {
  const int d = p.cloud.dim, k = p.physics().dofs_per_particle();
  std::vector<double> u(p.physics().dofs());
  for (std::size_t i = 0; i < p.cloud.size(); ++i)
    for (int a = 0; a < k; ++a) u[i * k + a] = 1e-4 * (a + 1) * p.cloud.x[i * d] + 2e-3 * std::pow(p.cloud.x[i * d + 1], 2);
  return u;
}

}  // namespace

TEST_CASE("a correspondence model's output fields through Model are its own stress and gradient", "[scene][model_slot]") {
  Problem p = build_problem(parse_scene(test::pulled_bar + "probes:\n  - {name: tip, point: [0.06, 0.006], field: von_mises}\n",
                                        "bar.yaml"));
  const Model& model = p.physics();
  const CorrespondenceModel& m = p.as<CorrespondenceModel>();
  const std::vector<double> u = state(p);
  const std::vector<OutputField> fields = model.output_fields(u.data(), true, true);
  std::vector<double> sigma, H(u.size() * 2);
  m.stress3(u.data(), sigma);
  m.gradient(u.data(), H.data());
  CHECK(field(fields, "stress").values == sigma);
  CHECK(field(fields, "displacement_gradient").values == H);
  CHECK(field(fields, "stress_gradient").values == stress_gradient(m, sigma));
  CHECK(model.stress_measure(u.data()) == sigma);
  const auto& vm = field(fields, "von_mises").values;
  for (std::size_t i = 0; i < m.particles(); ++i) CHECK(vm[i] == von_mises(sigma.data() + i * 9));
  // A snapshot's fields, in the order the .vtu lists them (the consistent formulation's surface stress).
  const std::vector<OutputField> snapshot = model.output_fields(u.data());
  std::vector<std::string> names;
  for (const auto& f : snapshot) names.push_back(f.name);
  CHECK(names == std::vector<std::string>{"displacement", "stress", "von_mises", "mean_stress", "volume",
                                          "surface_stress", "surface_von_mises"});
  CHECK(model.history() == nullptr);
  // Probes through the readout: the same value as from the concrete fields.
  const ProbeReadout readout(p, u);
  const ProbeFields concrete{p.cloud, u, sigma, H};
  CHECK(readout.point(p.probes.at(0)) == point_probe_value(p.probes.at(0), concrete));
  // The plan: the model's own lines.
  CHECK(plan_text(model, "dimension") == ", plane stress");
  CHECK(plan_text(model, "model") == "correspondence, consistent formulation, stabilization C_hg = 0.5");
  CHECK(plan_text(model, "consistent G~").find("boundary facets") != std::string::npos);
  CHECK(model.not_assembled().at(0) == "Hessian (operator order 2 keeps the fit's gradient only)");
}

TEST_CASE("a thin plate's output fields through Model are its deflection and moments", "[scene][model_slot][plate]") {
  Problem p = build_problem(parse_scene(R"(
name: plate
dimension: 2
geometry: {box: {min: [0.0, 0.0], max: [0.1, 0.1]}, thickness: 0.002}
discretization: {dx: 0.01, horizon: {ratio: 2.015}}
material: {type: linear_elastic, E: 2.0e11, nu: 0.3, density: 7800.0}
model: {type: thin_plate, stabilization: 0}
boundary:
  - {region: left, support: simply_supported}
  - {region: right, support: clamped}
  - {region: all, pressure: 100.0}
probes:
  - {name: mid, point: [0.05, 0.05], field: deflection}
  - {name: across, line: {from: [0.0, 0.05], to: [0.1, 0.05]}, field: deflection}
)", "plate.yaml"));
  const Model& model = p.physics();
  const ThinPlateModel& plate = p.as<ThinPlateModel>();
  CHECK_THROWS_AS(p.as<CorrespondenceModel>(), std::logic_error);
  const std::vector<double> w = state(p);
  const std::vector<OutputField> fields = model.output_fields(w.data());
  std::vector<double> M(w.size() * 3);
  plate.moments(w.data(), M.data());
  CHECK(field(fields, "deflection").values == w);
  CHECK(model.stress_measure(w.data()) == M);
  const auto& M9 = field(fields, "moment").values;
  for (std::size_t i = 0; i < w.size(); ++i) {
    CHECK(M9[i * 9] == M[i * 3]);
    CHECK(M9[i * 9 + 1] == M[i * 3 + 1]);
    CHECK(M9[i * 9 + 4] == M[i * 3 + 2]);
  }
  CHECK(field(fields, "volume").values == p.cloud.volume);
  CHECK(model.history() == nullptr);
  const ProbeReadout readout(p, w);
  CHECK(readout.point(p.probes.at(0)) == w[p.probes.at(0).particles.at(0)]);
  CHECK(readout.line_header(p.probes.at(1).spec) == std::vector<std::string>{"s", "x", "y", "z", "deflection"});
  const std::vector<double> row = readout.line_row(p.probes.at(1), 0);
  CHECK(row.at(4) == w[p.probes.at(1).particles.at(0)]);
  CHECK(plan_text(model, "dimension") == ", thin plate");
  CHECK(plan_text(model, "edges") == "left simply supported, right clamped, bottom free, top free");
  CHECK(plan_text(model, "model").find("thin_plate, D0 = ") == 0);
  CHECK(model.not_assembled() ==
        std::vector<std::string>{"gradient operator G and stabilization S of elasticity (no correspondence model)",
                                 "plate stabilization (C_hg = 0)"});
}
