#include "curved_surface_note.hpp"

#include <cstdio>

#include "perinom/geometry/surface_bend.hpp"

namespace perinom::cli {

std::string curved_surface_note(const Problem& p) {
  if (p.scene.model.type != "correspondence" || !p.scene.body_files.given() || p.facets.empty()) return "";
  const SurfaceBend bend =
      tightest_concave_bend(p.facets, p.cloud, p.scene.geometry.thickness, p.scene.discretization.dx, kBendSpacings);
  if (!bend.found()) return "";
  const int d = p.facets.dim;
  const double* c = &p.facets.centroid[bend.facet * d];
  char where[160];
  if (d == 2) std::snprintf(where, sizeof where, "(%.6g, %.6g)", c[0], c[1]);
  else std::snprintf(where, sizeof where, "(%.6g, %.6g, %.6g)", c[0], c[1], c[2]);
  char text[900];
  std::snprintf(text, sizeof text,
                "the surface bends round a void at %s with a radius of %.3g m, %.2g spacings (the particles' there, "
                "or dx when larger): the stress at such a surface converges with that number and reads low (a "
                "plate's hole on body-fitted particles, its edge sigma_xx with the consistent formulation: -26%%, "
                "-11%%, -2.1%% reconstructed at 2.5, 5 and 10 spacings; -35%%, -21%%, -11%% at the nearest particle; "
                "docs/verification/README.md)%s; refine the mesh there (and dx with it) and read the stress with a probe's "
                "reconstruct: true",
                where, bend.radius, bend.spacings,
                bend.spacings < 1.0 ? "; a hole narrower than a spacing is averaged over by every horizon round it, "
                                      "and the stress beside it can take the wrong sign"
                                    : "");
  return text;
}

}  // namespace perinom::cli
