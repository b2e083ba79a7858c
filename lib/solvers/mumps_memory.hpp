#pragma once
/// @file The memory MUMPS's factors will take, from MUMPS's own analysis, checked before the
/// first factorization (Newton with solver.linear_solver mumps). The ordering MUMPS chooses
/// (METIS or PT-Scotch, or AMD) is its own, so the fill count UMFPACK's check uses
/// (fill_ordering.hpp) would not say it; MUMPS's analysis does: INFO(15), its estimate of all
/// its data for an in-core factorization on each process, by which it sizes its work space.
/// Without this check a MUMPS factorization too large for the machine would meet the kernel's
/// OOM killer, with no message and no output (as UMFPACK's did before its check).
#include <petscmat.h>

namespace perinom::detail {

/// What MUMPS's analysis of a matrix predicts.
struct MumpsPrediction {
  double largest_bytes = 0.0;  ///< the largest process's estimate (INFOG(16), MB of 10^6 bytes)
  double total_bytes = 0.0;    ///< summed over the processes (INFOG(17))
  double seconds = 0.0;        ///< the analysis's wall time
};

/// Runs MUMPS's analysis of J (assembled; LDL^T when `symmetric`, else LU) with the options
/// the solve's factorization reads (-mat_mumps_icntl_*), and frees it.
MumpsPrediction predict_mumps_factors(Mat J, bool symmetric);

/// Throws InputError (exit 2) on every rank when a process's estimate, beside what the
/// process holds, exceeds the room of the most crowded rank: --max-memory (`limit`, a bound for
/// each rank), or without it the memory available on its host shared among the ranks there.
void require_mumps_memory(const MumpsPrediction& p, PetscInt unknowns, double limit);

}  // namespace perinom::detail
