#include "locking_warning.hpp"

#include <cstdio>

#include "classical_mesh_note.hpp"
#include "curved_surface_note.hpp"
#include "diagnostics.hpp"
#include "lattice_hole_note.hpp"
#include "layer_support_note.hpp"
#include "point_tie_note.hpp"
#include "precrack_row_note.hpp"
#include "point_volume_note.hpp"
#include "thick_plate_note.hpp"
#include "thin_body_note.hpp"

namespace perinom::cli {

std::string locking_warning(const Problem& p) {
  const Scene& s = p.scene;
  if (s.model.type != "correspondence" || (s.model.formulation == "classical" && s.model.operator_order == 2)) return "";
  const double ratio = s.material.lambda() / s.material.mu();
  if (!(ratio >= kLockingLambdaOverMu)) return "";
  const ThinPlace place = thinnest_place(p, kLockingParticles);
  if (place.where.empty()) return "";
  char buf[1280];
  std::snprintf(buf, sizeof buf,
                "material.nu = %.10g is nearly incompressible (lambda / mu = %.4g) and the body is %d particles across %s: "
                "model.formulation %s with operator_order %d locks in bending across so few (a plane-strain "
                "cantilever's tip deflection against FEM at 4 / 8 / 16 particles across, consistent order 2: nu 0.3 "
                "+4.5 / +2.3 / +0.6%%, nu 0.45 -3.4 / +1.9 / +0.6%%, nu 0.49 -28 / +1.2 / +0.5%%, nu 0.499 -70 / -2.9 / "
                "+0.2%%, nu 0.4999 -82 / -21 / -1.2%%; classical order 1 at nu 0.499: -66 / +13 / +3.2%%; "
                "in 3-D, sides free, nu 0.3 -> 0.499 made it 5.8 / 2.2%% stiffer at 4 / 8 across, beam theory 0.1%% softer; "
                "docs/verification/README.md): model.formulation classical with operator_order 2 did not lock "
                "(+6.5 / +2.0 / +0.7%% at every nu), or refine dx",
                s.material.nu, ratio, place.across, place.where.c_str(), s.model.formulation.c_str(),
                s.model.operator_order);
  return buf;
}

std::string plastic_collapse_note(const Problem& p) {
  if (p.scene.model.type != "correspondence" || !p.scene.plasticity) return "";
  if (p.scene.model.stabilization_scale == "secant")
    return "material drucker_prager, model.stabilization_scale secant: the stabilization follows each particle's "
           "secant shear stiffness, and a collapse load levels off (Prandtl's strip footing, verification/footing: "
           "1.20 / 1.15 / 1.08 times (2 + pi) k at a settlement of 15% of its half-width with 4 / 8 / 16 particles "
           "across it, rising 0.1-1.3% of the limit load over the last third, where CalculiX's CPE8R levels off at "
           "1.04 / 1.02 / 1.01; the elastic default: 1.56 / 1.40 / 1.26, still rising; docs/verification/README.md)";
  return "material drucker_prager: a body that collapses by a mechanism (a footing, a slope) is over-stiff in "
         "plastic flow and its load does not level off at the limit load: Prandtl's strip footing (phi = 0, plane "
         "strain, verification/footing) carried 1.30 / 1.24 / 1.17 times (2 + pi) k at a settlement of 5% of its "
         "half-width with 4 / 8 / 16 particles across that half-width, and 1.56 / 1.40 / 1.26 at 15%, still rising, "
         "where CalculiX's CPE8R levels off at 1.04 / 1.02 / 1.01 (docs/verification/README.md): a limit load read "
         "from such a run is too high, more so the coarser the dx. The stabilization (model.stabilization, elastic) "
         "resists the mechanism's flow: model.stabilization_scale: secant (S follows each particle's secant shear "
         "stiffness) levels off at 1.20 / 1.15 / 1.08 by 15%";
}

void print_body_notes(const Problem& p) {
  if (const std::string volumes = point_volume_warning(p); !volumes.empty()) warn("%s", volumes.c_str());
  if (const std::string thin = thin_body_note(p); !thin.empty()) note("%s", thin.c_str());
  if (const std::string thick = thick_plate_note(p); !thick.empty()) note("%s", thick.c_str());
  if (const std::string hole = lattice_hole_note(p); !hole.empty()) note("%s", hole.c_str());
  if (const std::string bend = curved_surface_note(p); !bend.empty()) note("%s", bend.c_str());
  if (const std::string tie = point_tie_note(p); !tie.empty()) note("%s", tie.c_str());
  if (const std::string row = precrack_row_note(p); !row.empty()) note("%s", row.c_str());
  if (const std::string locking = locking_warning(p); !locking.empty())
    warn("%s", locking.c_str());
  if (const std::string plastic = plastic_collapse_note(p); !plastic.empty())
    note("%s", plastic.c_str());
  if (const std::string layer = layer_support_note(p); !layer.empty()) note("%s", layer.c_str());
  if (const std::string classical = classical_mesh_note(p); !classical.empty()) note("%s", classical.c_str());
}

}  // namespace perinom::cli
