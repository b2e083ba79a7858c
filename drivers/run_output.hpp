#pragma once
// What `perinom run` writes of a solve's history, serial or distributed.
#include <string>

#include "perinom/io/json_writer.hpp"
#include "perinom/solvers/history.hpp"

namespace perinom::cli {

/// The history as CSV, one row per recorded iteration or step.
void write_history(const std::string& path, const History& h);

/// A Verlet history's energy balance at the end (kinetic + strain + released - work, against
/// the initial energy) over the largest work or energy recorded, as solver["energy_balance"];
/// prints a warning beyond 1%: the solver's guard stops a run only far beyond it
/// (solver.energy_tolerance). A history without energies adds nothing.
void add_energy_balance(const History& h, io::Json& solver);

}  // namespace perinom::cli
