#pragma once
// How much memory a scene will take, from the scene alone, before anything is allocated:
// the particles from the lattice's cell counts (less the holes' share of the box), the
// bonds from the horizon by counting lattice offsets (exact on a full box without jitter),
// and the bytes from measured costs per bond and per particle of each model (calibrated
// against the peak resident memory, VmHWM, of `perinom check`; docs/scene-format.md gives
// the table and its accuracy). `perinom check` and `perinom run` print it and refuse a
// scene that would not fit.
#include <cstddef>
#include <string>

#include "perinom/core/memory.hpp"
#include "perinom/scene/scene.hpp"

namespace perinom::cli {

struct MemoryEstimate {
  double particles = 0.0;
  double bonds = 0.0;
  double bytes = 0.0;     ///< the expected peak resident size of the whole process
  double baseline = 0.0;  ///< of which the process before the build (code, libraries)
  std::string key;        ///< the key to change when it is too much: discretization.dx or the horizon's
  /// False for a body from files (geometry.mesh, geometry.points): its particle count is in
  /// the file, which is read only when the problem is built; nothing is estimated then.
  bool known = true;
};

MemoryEstimate estimate_memory(const Scene& scene);

/// The Newton Jacobian's share of the peak for `particles` and `bonds` (a whole scene's, or a
/// rank's local ones), with its factors; 0 when the scene solves no Newton (solver.type,
/// solver.check).
double jacobian_bytes(const Scene& scene, double particles, double bonds);

/// Prints the estimate and throws an InputError naming the key if it exceeds `limit` bytes
/// (0: available_memory()). `limit_given` says the limit came from --max-memory.
void require_memory(const Scene& scene, const MemoryEstimate& e, double limit, bool limit_given);

}  // namespace perinom::cli
