#pragma once
/// @file The memory MUMPS's factors will take, from MUMPS's own analysis, checked before the
/// first factorization (Newton with solver.linear_solver mumps). The ordering MUMPS chooses
/// (METIS or PT-Scotch, or AMD) is its own, so the fill count UMFPACK's check uses
/// (fill_ordering.hpp) would not say it; MUMPS's analysis does: INFO(15), its estimate of all
/// its data for an in-core factorization on each process, by which it sizes its work space.
/// Without this check a MUMPS factorization too large for the machine would meet the kernel's
/// OOM killer, with no message and no output (as UMFPACK's did before its check).
#include <petscpc.h>

namespace perinom::detail {

/// What MUMPS's analysis of a matrix predicts.
struct MumpsPrediction {
  double largest_bytes = 0.0;  ///< the largest process's estimate (INFOG(16), MB of 10^6 bytes)
  double total_bytes = 0.0;    ///< summed over the processes (INFOG(17))
  double seconds = 0.0;        ///< the analysis's wall time
};

/// Runs the analysis (ordering and symbolic factorization) of J by the MUMPS factor of `pc`,
/// the preconditioner of Newton's linear solve (PCCHOLESKY when `symmetric`, else PCLU, with
/// MUMPS), as its set-up would, and reads what it predicts. The set-up then finds it done
/// (PETSc's MUMPS interface analyses a factor once), so nothing is repeated. Returns nothing
/// predicted (zeros) when the options made `pc` something else.
MumpsPrediction analyse_mumps_factors(PC pc, Mat J, bool symmetric);

/// Throws InputError (exit 2) on every rank when a process's estimate, beside what the
/// process holds, exceeds the room of the most crowded rank: --max-memory (`limit`, a bound for
/// each rank), or without it the memory available on its host shared among the ranks there.
void require_mumps_memory(const MumpsPrediction& p, PetscInt unknowns, double limit);

}  // namespace perinom::detail
