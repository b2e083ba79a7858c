#pragma once
/// @file PETSc in perinom: whether this build has it, the options a user passes through, and
/// its end. PETSc (and with it MPI) starts only when a solve needs it, so a scene that uses
/// no PETSc solver pays nothing for it.
#include <string>

namespace perinom {

/// True when the library was built with PETSc (Newton with solver.linear_solver mumps | gamg).
bool petsc_available();

/// PETSc's options ("-ksp_type gmres -pc_type gamg -ksp_monitor ..."), given to every PETSc
/// solve that follows; they are applied after perinom's own choices and so override them.
/// Throws InputError when this build has no PETSc.
void set_petsc_options(const std::string& options);

/// Ends PETSc (and MPI) if a solve started it; the program calls it once before it exits.
void finalize_petsc();

}  // namespace perinom
