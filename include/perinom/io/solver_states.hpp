#pragma once
/// @file A solver's resumable state as checkpoint records (io/checkpoint.hpp) and back: every
/// field of AdrState, VerletState or LoadPathState under its name, prefixed adr., verlet. or
/// load_path. (load_path.plastic: the model's committed history, ModelHistory::
/// values_per_particle() reals a particle, with load_path.flags; stage_value0 flattened with
/// stage_value0_sizes). A new solver state adds its pair here.
#include <cstddef>

#include "perinom/io/checkpoint.hpp"
#include "perinom/solvers/adr.hpp"
#include "perinom/solvers/load_path.hpp"
#include "perinom/solvers/verlet.hpp"

namespace perinom::io {

void put_state(Checkpoint& c, const AdrState& s);
void put_state(Checkpoint& c, const VerletState& s);
void put_state(Checkpoint& c, const LoadPathState& s);

/// The records back; each throws InputError naming a record that is missing or of the
/// wrong size (vectors of `dofs` values).
AdrState adr_state(const Checkpoint& c, std::size_t dofs);
VerletState verlet_state(const Checkpoint& c, std::size_t dofs);
/// `history_values`: the model's ModelHistory::values_per_particle() (0 without history).
LoadPathState load_path_state(const Checkpoint& c, std::size_t dofs, std::size_t history_values);

}  // namespace perinom::io
