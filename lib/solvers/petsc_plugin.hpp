#pragma once
/// @file The PETSc module's entry (internal to lib/solvers): libperinom_petsc.so, built where
/// PETSc is found, is loaded by libperinom only when a solve asks for PETSc, so PETSc, MPI and
/// their libraries (about 30 MB resident, 130 shared objects) cost nothing to a scene that
/// does not use them.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "perinom/solvers/newton.hpp"

namespace perinom::detail {

struct PetscPlugin {
  /// solve_newton through PETSc SNES; `options` are the user's PETSc options, inserted before
  /// PETSc reads any (PETSc starts at the first call).
  SolveReport (*solve_newton)(TangentModel& model, const Loading& loading, const NewtonOptions& options,
                              std::vector<double>& u, Progress* progress, const std::string& petsc_options);
  /// Ends PETSc (and MPI) if a solve started it.
  void (*finalize)();

  // The distributed path's communication (petsc_ranks.hpp); the first call starts PETSc.
  void (*world)(int* rank, int* size);
  void* (*halo_create)(std::size_t owned, const std::int64_t* ghosts, std::size_t count, int block,
                       double* values);
  void (*halo_update)(void* halo);
  void (*halo_add_to_owners)(void* halo);
  void (*halo_destroy)(void* halo);
  void (*reduce)(double* values, int count, bool max);
  void (*gather)(const double* owned, std::size_t count, double* root);
  void (*barrier)();
  void (*abort_ranks)(int code);
  /// PT-Scotch on a symmetric graph (petsc_partition.hpp).
  void (*partition_graph)(std::size_t n, const std::int64_t* offsets, const std::int32_t* cols, int parts,
                          int* rank_of);
};

/// The loaded module; throws InputError naming `what` when this build has no PETSc.
const PetscPlugin& petsc_plugin(const std::string& what);

}  // namespace perinom::detail

/// The module's one exported symbol.
extern "C" const perinom::detail::PetscPlugin* perinom_petsc_plugin();
