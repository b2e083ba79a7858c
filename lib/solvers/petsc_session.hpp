#pragma once
/// @file The one PETSc session of a process, in the PETSc module (internal to lib/solvers):
/// started by the first solve that needs it.
#include <petscsys.h>

#include <string>

namespace perinom::detail {

/// Starts PETSc once, with the user's options inserted first (errors are kept, not printed:
/// check() turns them into exceptions); later calls insert the options again.
void start_petsc(const std::string& options);

/// Ends PETSc (and MPI) if it was started.
void end_petsc();

/// Throws SolveError naming `what` and PETSc's message when code is not 0.
void check(PetscErrorCode code, const char* what);

}  // namespace perinom::detail
