#include "classical_mesh_note.hpp"

namespace perinom::cli {

std::string classical_mesh_note(const Problem& p) {
  const Scene& s = p.scene;
  if (s.model.type != "correspondence" || s.model.formulation != "classical" || !s.body_files.given()) return "";
  const bool bare_points = s.body_files.mesh.empty() && s.body_files.facets.empty();
  return std::string("model.formulation classical on a body from ") + (s.body_files.mesh.empty() ? "a point file" : "a mesh") +
         ": its surface effect is larger on an irregular cloud than on the lattice (a uniform strain on an L-shaped "
         "body, verification/formulation/classical_mesh.py: the moved faces' reactions -7.5% and -19% from "
         "triangles, -2.4% and -6.5% from quadrilaterals, particle stress up to 160% off near the surface; a "
         "lattice box -1.9% and 40%); the consistent formulation (the default) reproduces it to 1e-13" +
         (bare_points ? " and needs geometry.facets" : "");
}

}  // namespace perinom::cli
