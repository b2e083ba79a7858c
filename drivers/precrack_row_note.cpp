#include "precrack_row_note.hpp"

#include <cstdio>

#include "perinom/fracture/precrack.hpp"
#include "point_text.hpp"

namespace perinom::cli {

std::string precrack_row_note(const Problem& p) {
  const Scene& s = p.scene;
  std::string said;
  for (std::size_t k = 0; k < s.precracks.size(); ++k) {
    const std::vector<ParticleId> on = particles_on(p.cloud, s.precracks[k]);
    if (on.empty()) continue;
    char text[300];
    std::snprintf(text, sizeof text, "%sprecracks[%zu] passes through %zu particle%s (the first: particle %lld at (%s))",
                  said.empty() ? "" : "; ", k, on.size(), on.size() == 1 ? "" : "s", static_cast<long long>(on.front()),
                  point_text(p.cloud.point(on.front()), p.cloud.dim).c_str());
    said += text;
  }
  if (said.empty()) return "";
  return said + ": a bond from a particle on the crack is not cut, and rounding decides on which side of the line "
                "such a particle falls, so some bonds across the crack stay (put a crack between particle rows, "
                "half a spacing off them)";
}

}  // namespace perinom::cli
