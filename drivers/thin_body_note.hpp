#pragma once
// A body few particles across one side resolves bending across it coarsely, and nothing in
// the answer shows it: a wall 3 particles thick bent 14% more than the Kirchhoff plate,
// with exit 0 and a converged residual. Run and check say so (and where) before the solve.
#include <string>

#include "perinom/scene/problem.hpp"

namespace perinom::cli {

/// Below this many particles across its thinnest side a body gets the note; with the
/// first-order fit (model.operator_order 1, the classical formulation's default), whose
/// cantilever is 17% soft at 8 across and 4.9% at 16, below the second.
inline constexpr int kThinBodyParticles = 8;
inline constexpr int kThinBodyParticlesFirstOrder = 16;
int thin_body_particles(const Scene& s);

/// The thinnest place of a correspondence body fewer than `below` particles across (none:
/// `where` empty): its particles across and where ("along y from (x, y)"), measured by
/// thinnest_wall on the body's facets (a lattice's computed here when the formulation keeps
/// none: a ligament beside a hole, a tube's wall; a point file without facets: its
/// bounding box).
struct ThinPlace {
  int across = 0;
  std::string where;
};
ThinPlace thinnest_place(const Problem& p, int below);

/// "" or the note (without a prefix) for a correspondence body fewer than
/// thin_body_particles across somewhere (thinnest_place), with the measured errors of its
/// fit's order at 4, 8 and 16 across.
std::string thin_body_note(const Problem& p);

}  // namespace perinom::cli
