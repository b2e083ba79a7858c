// What the drivers and the load path ask of a correspondence model through Model and
// ModelHistory: its output fields, its stress measure, its lines of the plan, and its
// law's history.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "perinom/fracture/bond_measures.hpp"
#include "perinom/materials/measures.hpp"
#include "perinom/operators/hourglass_energy.hpp"
#include "perinom/models/correspondence.hpp"

namespace perinom {
namespace {

const char* formulation_name(Formulation f) {
  switch (f) {
    case Formulation::classical: return "classical";
    case Formulation::improved: return "improved";
    case Formulation::strong: return "strong";
    case Formulation::consistent: return "consistent";
  }
  return "";
}

std::string format(const char* fmt, double a) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, a);
  return buf;
}



}  // namespace

std::vector<OutputField> CorrespondenceModel::output_fields(const double* u, bool probe_fields,
                                                            bool gradients) const {
  const int d = dim_;
  const std::size_t n = particles();
  std::vector<OutputField> out;
  OutputField u3{"displacement", 3, std::vector<double>(n * 3, 0.0)};
  for (std::size_t i = 0; i < n; ++i)
    for (int a = 0; a < d; ++a) u3.values[i * 3 + a] = u[i * d + a];
  out.push_back(std::move(u3));
  std::vector<double> sigma;
  stress3(u, sigma);
  OutputField vm{"von_mises", 1, std::vector<double>(n)}, mean{"mean_stress", 1, std::vector<double>(n)};
  for (std::size_t i = 0; i < n; ++i) {
    vm.values[i] = von_mises(sigma.data() + i * 9);
    const double* s = sigma.data() + i * 9;
    mean.values[i] = (s[0] + s[4] + s[8]) / 3.0;
  }
  // The stress gradient by G: for the surface stress and for reconstructing probes.
  const BoundaryFacets& facets = trace_.facets();
  std::vector<double> grad_sigma;
  if (!facets.empty() || gradients) {
    grad_sigma.resize(sigma.size() * d);
    G_.apply(sigma.data(), 9, grad_sigma.data());
  }
  out.push_back({"stress", 9, sigma});
  out.push_back(std::move(vm));
  out.push_back(std::move(mean));
  out.push_back({"volume", 1, volume_});
  // The stress at the surface: each facet owner's stress reconstructed at its facets'
  // centroids, area-weighted (the facets of a corner particle: their mean); elsewhere the
  // particle's own stress (finite: the snapshot guard refuses NaN, and a user's colour map
  // then shows the whole body).
  if (!facets.empty()) {
    std::vector<double> area(n, 0.0), surface_sigma(n * 9, 0.0), surface_vm(n, 0.0);
    double s9[9];
    for (std::size_t k = 0; k < facets.size(); ++k) {
      const std::size_t i = facets.particle[k];
      const double* y = facets.centroid.data() + k * d;
      for (int c = 0; c < 9; ++c) {
        s9[c] = sigma[i * 9 + c];
        for (int b = 0; b < d; ++b) s9[c] += grad_sigma[(i * 9 + c) * d + b] * (y[b] - x_[i * d + b]);
      }
      for (int c = 0; c < 9; ++c) surface_sigma[i * 9 + c] += facets.area[k] * s9[c];
      area[i] += facets.area[k];
    }
    for (std::size_t i = 0; i < n; ++i) {
      for (int c = 0; c < 9; ++c)
        surface_sigma[i * 9 + c] = area[i] > 0.0 ? surface_sigma[i * 9 + c] / area[i] : sigma[i * 9 + c];
      surface_vm[i] = von_mises(surface_sigma.data() + i * 9);
    }
    out.push_back({"surface_stress", 9, std::move(surface_sigma)});
    out.push_back({"surface_von_mises", 1, std::move(surface_vm)});
  }
  // Improved and strong formulations: subregion 1 = E (strong form), 0 = D (weak form).
  if (!surface_.in_band.empty()) {
    out.push_back({"subregion_E", 1, std::vector<double>(surface_.in_band.begin(), surface_.in_band.end())});
    out.push_back({"surface", 1, std::vector<double>(surface_.on_surface.begin(), surface_.on_surface.end())});
  }
  // Broken bonds: the volume-weighted share of each family that is gone (seed 002 eq. 88),
  // the break event a particle first lost a bond in (the order a crack grew in), and the
  // largest principal stress (what the stress criterion reads).
  if (fracture_fields_ || graph_->broken() > 0) {
    out.push_back({"damage", 1, damage(*graph_, volume_)});
    out.push_back({"break_event", 1, first_break_event(*graph_)});
  }
  if (fracture_fields_) {
    OutputField s1{"max_principal_stress", 1, std::vector<double>(n)};
    for (std::size_t i = 0; i < n; ++i) s1.values[i] = max_principal_stress(sigma.data() + i * 9);
    out.push_back(std::move(s1));
    // Where the stabilization holds zero-energy modes (first order: the classical fracture
    // model's; the second-order fit's energy has another form and is not written).
    if (c_hg_ > 0.0 && order_ == 1)
      out.push_back({"hourglass_energy_density", 1, hourglass_energy_density(G_, u, c_hg_ * 2.0 * material_.mu())});
  }
  // The law's own fields (its committed states; "stress" is the model's above).
  for (const LawField& field : law_->fields()) {
    if (field.name == "stress") continue;
    OutputField o{field.name, field.components, {}};
    law_->field(field.name, nullptr, o.values);
    out.push_back(std::move(o));
  }
  if (probe_fields) {
    OutputField H{"displacement_gradient", d * d, std::vector<double>(n * d * d)};
    gradient(u, H.values.data());
    OutputField eq{"equivalent_strain", 1, std::vector<double>(n)};
    // Elastic plane stress: eps_zz = -nu / (1 - nu) (eps_xx + eps_yy); plane strain: 0.
    const double zz = d == 2 && material_.plane == PlaneCondition::stress ? -material_.nu / (1.0 - material_.nu) : 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double* Hi = H.values.data() + i * d * d;
      eq.values[i] = equivalent_strain(Hi, d, d == 2 ? zz * (Hi[0] + Hi[3]) : 0.0);
    }
    out.push_back(std::move(H));
    out.push_back(std::move(eq));
  }
  if (gradients) out.push_back({"stress_gradient", 9 * d, std::move(grad_sigma)});
  return out;
}

std::vector<double> CorrespondenceModel::stress_measure(const double* u) const {
  std::vector<double> sigma;
  stress3(u, sigma);
  return sigma;
}

std::vector<PlanLine> CorrespondenceModel::plan() const {
  std::vector<PlanLine> lines;
  if (dim_ == 2) lines.push_back({"dimension", material_.plane == PlaneCondition::strain ? ", plane strain" : ", plane stress"});
  lines.push_back({"model", std::string("correspondence, ") + formulation_name(formulation_) +
                                " formulation, stabilization C_hg = " + format("%g", c_hg_) +
                                (secant_ ? ", each particle's scaled by its secant shear stiffness" : "")});
  if (formulation_ == Formulation::consistent) {
    const ConsistencyReport& c = consistency_;
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "%zu boundary facets; correction |G~ - G|/|G| = %.3g, %d CG iterations, column residual %.2g, "
                  "facet defect %.2g",
                  trace_.facets().size(), c.relative_change, c.iterations, c.residual, c.rhs_defect);
    lines.push_back({"consistent G~", buf});
  }
  if (formulation_ == Formulation::improved || formulation_ == Formulation::strong) {
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "E (strong form, within 2 delta of a surface): %zu particles, D (weak form): %zu, surface "
                  "particles: %zu",
                  surface_.band.size(), surface_.interior.size(),
                  static_cast<std::size_t>(std::count(surface_.on_surface.begin(), surface_.on_surface.end(), 1)));
    lines.push_back({"subregions", buf});
  }
  if (graph_->broken() > 0) {
    // Bonds cut before the run (precracks): what the crack removed, and who lost its family.
    const std::size_t detached = G_.detached().size();
    char buf[160];
    std::snprintf(buf, sizeof buf, "%zu of %zu bonds broken, %zu particle(s) detached", graph_->broken(),
                  graph_->bonds(), detached);
    lines.push_back({"broken bonds", buf});
  }
  return lines;
}

std::vector<std::string> CorrespondenceModel::not_assembled() const {
  const bool fit_kept = order_ == 2 && S_ && S_->level() == AssemblyLevel::matrix_free;
  std::vector<std::string> items = {order_ != 2 ? "Hessian (no second-order model)"
                                    : fit_kept  ? "Hessian as a field (the matrix-free stabilization keeps the fit's)"
                                                : "Hessian (operator order 2 keeps the fit's gradient only)"};
  if (c_hg_ <= 0.0) items.push_back("stabilization S (C_hg = 0)");
  return items;
}

// ModelHistory: the law's history (history() is nullptr when the law has none).
void CorrespondenceModel::set_history_mode(HistoryMode mode) { law_->history()->set_history_mode(mode); }
void CorrespondenceModel::commit_trial() { law_->commit(); }
std::size_t CorrespondenceModel::flag_violations(double tolerance) { return law_->history()->flag_violations(tolerance); }
std::vector<double> CorrespondenceModel::history_variable() const { return law_->history()->history_variable(); }
std::size_t CorrespondenceModel::values_per_particle() const { return law_->history()->values_per_particle(); }
HistoryState CorrespondenceModel::save_history() const { return law_->history()->save_history(); }
void CorrespondenceModel::restore_history(const HistoryState& s) {
  law_->history()->restore_history(s);
}
void CorrespondenceModel::reset_history() {
  law_->history()->reset_history();
}

}  // namespace perinom
