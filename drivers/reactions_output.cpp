#include "reactions_output.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "perinom/solvers/rounding_force.hpp"

namespace perinom::cli {
namespace {

std::string vector_text(const double* v, int n) {
  std::string out = "(";
  char buf[32];
  for (int a = 0; a < n; ++a) {
    std::snprintf(buf, sizeof buf, "%s%.6e", a ? ", " : "", v[a]);
    out += buf;
  }
  return out + ")";
}

double length(const double* v, int n) {
  double s = 0.0;
  for (int a = 0; a < n; ++a) s += v[a] * v[a];
  return std::sqrt(s);
}

}  // namespace

io::Json pin_results(const Problem& p) {
  io::Json out = io::Json::array();
  const int d = p.cloud.dim;
  std::string text;
  for (const auto& pin : p.pins) {
    io::Json j = io::Json::object(), x = io::Json::array(), c = io::Json::array();
    std::string held;
    for (int a = 0; a < d; ++a) x.push_back(p.cloud.x[pin.particle * d + a]);
    for (const int a : pin.components) {
      c.push_back(std::string(1, "xyz"[a]));
      held += std::string(held.empty() ? "" : ", ") + "xyz"[a];
    }
    j["particle"] = static_cast<long long>(pin.particle);
    j["position"] = x;
    j["components"] = c;
    out.push_back(j);
    text += (text.empty() ? "" : "; ") + std::string("particle ") + std::to_string(pin.particle) + " at " +
            vector_text(p.cloud.point(pin.particle), d) + " in " + held;
  }
  if (!p.pins.empty())
    std::printf("perinom: constraints rigid_body: pinned %s\n", text.c_str());
  return out;
}

void add_reaction_results(Model& model, const Loading& loading, double s, const std::vector<double>& u,
                          bool dynamic, io::Json& summary, double carried, double rounding) {
  if (!loading.has_supports()) return;
  const int dpp = model.dofs_per_particle();
  std::vector<double> fint(model.dofs()), R(loading.support_names.size() * dpp);
  model.follow_loads(loading, s);
  model.internal_force(u.data(), fint.data());
  loading.reactions(fint.data(), s, dpp, R.data());
  std::vector<double> applied(dpp, 0.0), total(dpp, 0.0);
  double gross = 0.0;  // sum of |f_k|: the scale when the loads balance
  if (loading.has_force())
    for (std::size_t k = 0; k < model.dofs(); ++k) applied[k % dpp] += loading.force_at(s, k), gross += std::abs(loading.force_at(s, k));
  model.sum_across_ranks(R.data(), int(R.size()));
  model.sum_across_ranks(applied.data(), dpp);
  model.sum_across_ranks(&gross, 1);
  io::Json reactions = io::Json::object();
  double largest = 0.0;
  for (std::size_t g = 0; g < loading.support_names.size(); ++g) {
    io::Json r = io::Json::array();
    for (int a = 0; a < dpp; ++a) r.push_back(R[g * dpp + a]), total[a] += R[g * dpp + a];
    reactions[loading.support_names[g]] = r;
    largest = std::max(largest, length(R.data() + g * dpp, dpp));
    std::printf("  reaction %s = %s N\n", loading.support_names[g].c_str(), vector_text(R.data() + g * dpp, dpp).c_str());
  }
  summary["reactions"] = reactions;
  // In a dynamic run the loads are balanced by inertia too: no equilibrium to check.
  if (dynamic) return;
  std::vector<double> sum(dpp);
  for (int a = 0; a < dpp; ++a) sum[a] = applied[a] + total[a];
  // Relative to the applied resultant; when the loads balance (a free body) or there are
  // none, to the sum of the nodal loads' magnitudes, or else to the largest reaction.
  const double net = length(applied.data(), dpp);
  const bool balanced = net <= 1e-6 * gross;
  const bool broke = gross == 0.0 && carried > largest;  // a load path broken apart, or unloaded
  const bool noise = rounding > 0.0;  // loads and reactions at rounding: the stiffness force
  const double scale = noise ? rounding : !balanced ? net : gross > 0.0 ? gross : broke ? carried : largest;
  const char* over = noise      ? "stiffness force (the loads and reactions are rounding)"
                     : !balanced ? "|applied|"
                     : gross > 0.0 ? "sum |nodal load|"
                     : broke      ? "largest reaction carried along the path"
                                  : "largest reaction";
  const double error = scale > 0.0 ? length(sum.data(), dpp) / scale : 0.0;
  std::printf("perinom: equilibrium: applied loads %s N, reactions %s N, error |applied + reactions| / %s = %.3e\n",
              vector_text(applied.data(), dpp).c_str(), vector_text(total.data(), dpp).c_str(), over, error);
  io::Json eq = io::Json::object(), ja = io::Json::array(), jr = io::Json::array();
  for (int a = 0; a < dpp; ++a) ja.push_back(applied[a]), jr.push_back(total[a]);
  eq["applied"] = ja;
  eq["reactions"] = jr;
  eq["error"] = error;
  eq["relative_to"] = std::string(over);
  eq["scale"] = scale;  // N: the value of relative_to
  summary["equilibrium"] = eq;
}

double largest_reaction_carried(const History& h) {
  double carried = 0.0;
  for (std::size_t c = 0; c + 1 < h.columns.size(); ++c) {
    const std::string& name = h.columns[c];
    if (name.size() < 4 || name.compare(name.size() - 3, 2, ".R") != 0) continue;
    for (std::size_t at = c; at < h.values.size(); at += h.columns.size()) carried = std::max(carried, std::abs(h.values[at]));
  }
  return carried;
}

void add_rounding_floor(const SolveReport& rep, io::Json& solver) {
  if (rep.stiffness_force <= 0.0) return;  // a dynamic run, or a solver that does not measure it
  solver["residual_force"] = rep.residual_force;
  solver["stiffness_force"] = rep.stiffness_force;
  solver["at_rounding_floor"] = rep.at_rounding_floor;
}

std::string residual_text(const SolveReport& rep) {
  char text[320];
  if (rep.at_rounding_floor)
    std::snprintf(text, sizeof text,
                  "residual %.3e over loads and reactions that are rounding; the residual force %.3e N is below the "
                  "%.3e N rounding leaves in internal forces of %.3e N",
                  rep.residual, rep.residual_force, rounding_force(rep.stiffness_force), rep.stiffness_force);
  else
    std::snprintf(text, sizeof text, "residual %.3e", rep.residual);
  return text;
}

}  // namespace perinom::cli
