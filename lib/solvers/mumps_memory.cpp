#include "mumps_memory.hpp"

#include <mpi.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "perinom/core/error.hpp"
#include "perinom/core/memory.hpp"
#include "petsc_session.hpp"

namespace perinom::detail {
namespace {

double mib(double bytes) { return bytes / 1048576.0; }

/// The number of ranks on this rank's host (they share its available memory).
int ranks_on_host() {
  MPI_Comm host = MPI_COMM_NULL;
  int count = 1;
  if (MPI_Comm_split_type(PETSC_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &host) == MPI_SUCCESS) {
    MPI_Comm_size(host, &count);
    MPI_Comm_free(&host);
  }
  return count;
}

}  // namespace

MumpsPrediction analyse_mumps_factors(PC pc, Mat J, bool symmetric) {
  MumpsPrediction p;
  PetscBool factor = PETSC_FALSE;
  check(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), symmetric ? PCCHOLESKY : PCLU, &factor),
        "PetscObjectTypeCompare");
  MatSolverType solver = nullptr;
  if (!factor || PCFactorGetMatSolverType(pc, &solver) || !solver || std::string(solver) != MATSOLVERMUMPS) return p;
  const double start = MPI_Wtime();
  check(PCSetOperators(pc, J, J), "PCSetOperators");
  check(PCFactorSetUpMatSolverType(pc), "PCFactorSetUpMatSolverType");
  Mat F = nullptr;
  check(PCFactorGetMatrix(pc, &F), "PCFactorGetMatrix");
  MatFactorInfo info;
  check(MatFactorInfoInitialize(&info), "MatFactorInfoInitialize");
  // No ordering is passed: MUMPS orders by its own choice (ICNTL(7)), as in the set-up.
  check(symmetric ? MatCholeskyFactorSymbolic(F, J, nullptr, &info) : MatLUFactorSymbolic(F, J, nullptr, nullptr, &info),
        "MUMPS's analysis of the Jacobian");
  PetscInt status = 0, largest = 0, total = 0;
  check(MatMumpsGetInfog(F, 1, &status), "MatMumpsGetInfog");
  if (status < 0) return p;  // (the set-up meets the same error and reports it)
  check(MatMumpsGetInfog(F, 16, &largest), "MatMumpsGetInfog");
  check(MatMumpsGetInfog(F, 17, &total), "MatMumpsGetInfog");
  p.largest_bytes = 1e6 * double(largest);
  p.total_bytes = 1e6 * double(total);
  p.seconds = MPI_Wtime() - start;
  return p;
}

void require_mumps_memory(const MumpsPrediction& p, PetscInt unknowns, double limit) {
  // Each rank's room; unknown (no limit, no figure from the system) counts as no bound.
  const double held = resident_bytes();
  const double available = available_memory();
  double room = limit > 0.0 ? limit - held : available > 0.0 ? available / ranks_on_host() : 1e300;
  // The least room and the most held over the ranks, so every rank decides alike.
  double worst[2] = {-room, held};
  MPI_Allreduce(MPI_IN_PLACE, worst, 2, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
  room = -worst[0];
  if (p.largest_bytes <= room) return;
  int ranks = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
  char text[700];
  std::snprintf(text, sizeof text,
                "solver.linear_solver: MUMPS's factors of the Jacobian (%lld unknowns; by MUMPS's analysis %.0f MiB on "
                "the largest of %d processes, INFOG(16), %.0f MiB on all, INFOG(17)) would need more than the %.0f MiB %s "
                "(a process holds up to %.0f MiB); use solver.linear_solver gamg (PETSc's multigrid: no factors), more "
                "processes under mpirun (on more hosts), solver.type adr, or a larger discretization.dx%s",
                static_cast<long long>(unknowns), mib(p.largest_bytes), ranks, mib(p.total_bytes), mib(std::max(room, 0.0)),
                limit > 0.0 ? "that --max-memory leaves a process" : "of memory available to a process",
                mib(worst[1]), limit > 0.0 ? "" : " (--max-memory overrides the limit)");
  throw InputError(text);
}

}  // namespace perinom::detail
