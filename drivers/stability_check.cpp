#include "stability_check.hpp"

#include <cstdio>

#include "diagnostics.hpp"

namespace perinom::cli {

const Loading& checked_loading(const Problem& p) { return p.stages.empty() ? p.loading : p.stages.front().loading; }

void print_spectrum(const SpectrumReport& r) {
  const bool dense = r.method == "dense";
  std::printf("  stability check  eigenvalues of M^-1 K on %zu free dofs (Galerkin reduction, %s, %.2f s):\n", r.dofs,
              r.method.c_str(), r.seconds);
  std::printf("    smallest real part          %.6e 1/s^2 (largest |lambda| %.6e%s)\n", r.min_real, r.max_abs,
              dense ? "" : "; both by iteration");
  if (dense) std::printf("    largest |Im| / max |lambda| %.3e\n", r.max_imag_relative);
  if (dense) std::printf("    negative real part          %zu (below -1e-9 max |lambda|)\n", r.negative);
  else if (r.method == "sparse LDL^T inertia")
    std::printf("    negative                    %zu (negative pivots of K; %zu zero)\n", r.negative, r.singular);
  else std::printf("    negative                    0 (K has a Cholesky factor)\n");
  if (dense) std::printf("    complex                     %zu (|Im| above 1e-8 max |lambda|)\n", r.complex);
  else std::printf("    complex                     0 (K is symmetric: every eigenvalue is real)\n");
  std::printf("    symmetry defect             %.3e (||K - K^T|| / ||K||, Frobenius)\n", r.symmetry_defect);
  std::printf("    growth rate                 %.6e 1/s (max Im sqrt(lambda))\n", r.growth_rate);
  std::printf("  %s\n", r.verdict().c_str());
}

void warn_if_unstable(Problem& p) {
  const std::string name = p.scene.model.formulation;
  if (name != "improved" && name != "strong") return;
  const Loading& loading = checked_loading(p);
  const SpectrumOptions options;
  const std::size_t n = free_dofs(p.physics(), loading);
  if (n > options.max_dofs) {
    warn("model.formulation %s: non-symmetric (strong-form rows near the surface) and "
                 "possibly unstable; the stability check was skipped: %zu free dofs exceed its limit of %zu "
                 "(perinom check --spectrum on a coarser discretization.dx); use consistent",
                 name.c_str(), n, options.max_dofs);
    return;
  }
  std::printf("perinom: model.formulation %s is non-symmetric: checking the stability of %zu free dofs\n", name.c_str(), n);
  std::fflush(stdout);
  const SpectrumReport r = stiffness_spectrum(p.physics(), loading, options);
  if (r.stable()) {
    std::printf("perinom: stability check: stable (symmetry defect %.2e, %.1f s)\n", r.symmetry_defect, r.seconds);
    return;
  }
  warn("model.formulation %s: the discrete problem is unstable (%zu eigenvalues of M^-1 K "
               "with negative real part, %zu complex, growth rate %.3e 1/s; perinom check --spectrum shows them); "
               "a static answer may be wrong; use consistent",
               name.c_str(), r.negative, r.complex, r.growth_rate);
}

}  // namespace perinom::cli
