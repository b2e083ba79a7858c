#include "lattice_hole_note.hpp"

namespace perinom::cli {

std::string lattice_hole_note(const Problem& p) {
  const Scene& s = p.scene;
  if (s.model.type != "correspondence" || s.geometry.holes.empty()) return "";
  const std::string& f = s.model.formulation;
  const std::string edge = f == "consistent" ? "31-49% low at dx = R/2.5 to R/10, not converging"
                           : f == "improved"  ? "-4.4% reconstructed at R/10"
                           : f == "classical" ? "+22% reconstructed at R/10"
                                              : "not measured for this formulation";
  return "geometry.holes: a hole cut from the lattice is a staircase of cells, with axis-aligned facets: the "
         "displacement converges (a plate with a hole, u_x at its end: within 0.7% at dx = R/2.5 to R/10), the stress "
         "at the hole's edge does not (the plate's sigma_xx at the edge with model.formulation " + f + ": " + edge +
         "; docs/verification/README.md); for stress at a curved surface use geometry.mesh (body-fitted particles: "
         "-2.1% at R/10)";
}

}  // namespace perinom::cli
