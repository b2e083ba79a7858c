#pragma once
/// @file Neighbour families in CSR form, and their dual-support (transpose).
#include <cstddef>
#include <vector>

#include "perinom/core/types.hpp"

namespace perinom {

/// Families H_i in compressed-row form: the neighbours of particle i are
/// neighbors[offsets[i] .. offsets[i+1]), sorted by id, never i itself.
/// support[i] is the radius delta_i of the family (m): the horizon for radius families,
/// the distance of the farthest neighbour for k-nearest families.
struct Families {
  std::vector<Offset> offsets{0};
  std::vector<ParticleId> neighbors;
  std::vector<double> support;

  std::size_t particles() const { return offsets.size() - 1; }
  std::size_t bonds() const { return neighbors.size(); }
  Offset begin(std::size_t i) const { return offsets[i]; }
  Offset end(std::size_t i) const { return offsets[i + 1]; }
};

/// Throws InputError unless f is families of a cloud of `particles` particles: one row each,
/// offsets non-decreasing from 0 to bonds(), every neighbour an index below `particles` and
/// not the particle itself, support empty or one radius a particle (naming the particle and
/// the neighbour). Row order is not checked: a rank's local_families are in local ids, not
/// sorted. O(bonds), once.
void check_families(const Families& f, std::size_t particles);

/// The dual-support H'_i = { j : i in H_j } in CSR form, with, for each of its entries,
/// the position of the bond (j, i) in the original family arrays (so per-bond data stored
/// with the families can be gathered in transposed order).
struct DualSupport {
  std::vector<Offset> offsets{0};
  std::vector<ParticleId> neighbors;
  std::vector<Offset> bond;  ///< position of bond (neighbors[k], i) in Families::neighbors
};

/// Builds the dual-support of f (a counting sort; O(bonds)).
DualSupport dual_support(const Families& f);

/// Memory of the families in bytes.
std::size_t memory_bytes(const Families& f);

}  // namespace perinom
