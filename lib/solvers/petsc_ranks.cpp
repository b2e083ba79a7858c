// The distributed path's communication through PETSc (petsc_ranks.hpp).
#include "petsc_ranks.hpp"

#include <petscvec.h>

#include <limits>
#include <vector>

#include "perinom/core/error.hpp"
#include "petsc_session.hpp"

namespace perinom::detail {
namespace {

PetscInt petsc_int(std::size_t v, const char* what) {
  if (v > static_cast<std::size_t>(std::numeric_limits<PetscInt>::max()))
    throw InputError(std::string(what) + ": more than PETSc's index type holds");
  return static_cast<PetscInt>(v);
}

}  // namespace

void world(int* rank, int* size) {
  start_petsc("");
  MPI_Comm_rank(PETSC_COMM_WORLD, rank);
  MPI_Comm_size(PETSC_COMM_WORLD, size);
}

void* halo_create(std::size_t owned, const std::int64_t* ghosts, std::size_t count, int block, double* values) {
  start_petsc("");
  std::vector<PetscInt> g(count);
  for (std::size_t k = 0; k < count; ++k) g[k] = petsc_int(static_cast<std::size_t>(ghosts[k]), "a ghost's index");
  Vec v = nullptr;
  check(VecCreateGhostBlockWithArray(PETSC_COMM_WORLD, block, petsc_int(owned * block, "the owned values"),
                                     PETSC_DECIDE, petsc_int(count, "the ghosts"), g.data(), values, &v),
        "VecCreateGhostBlockWithArray");
  return v;
}

void halo_update(void* halo) {
  Vec v = static_cast<Vec>(halo);
  check(VecGhostUpdateBegin(v, INSERT_VALUES, SCATTER_FORWARD), "VecGhostUpdateBegin");
  check(VecGhostUpdateEnd(v, INSERT_VALUES, SCATTER_FORWARD), "VecGhostUpdateEnd");
}

void halo_add_to_owners(void* halo) {
  Vec v = static_cast<Vec>(halo);
  check(VecGhostUpdateBegin(v, ADD_VALUES, SCATTER_REVERSE), "VecGhostUpdateBegin");
  check(VecGhostUpdateEnd(v, ADD_VALUES, SCATTER_REVERSE), "VecGhostUpdateEnd");
}

void halo_destroy(void* halo) {
  Vec v = static_cast<Vec>(halo);
  VecDestroy(&v);
}

void reduce(double* values, int count, bool max) {
  MPI_Allreduce(MPI_IN_PLACE, values, count, MPI_DOUBLE, max ? MPI_MAX : MPI_SUM, PETSC_COMM_WORLD);
}

void gather(const double* owned, std::size_t count, double* root) {
  int rank = 0, size = 1;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  if (count > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw InputError("gather: more values on a rank than MPI counts");
  int mine = static_cast<int>(count);
  std::vector<int> counts(size), displs(size, 0);
  MPI_Gather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, PETSC_COMM_WORLD);
  for (int r = 1; r < size; ++r) displs[r] = displs[r - 1] + counts[r - 1];
  MPI_Gatherv(owned, mine, MPI_DOUBLE, root, counts.data(), displs.data(), MPI_DOUBLE, 0, PETSC_COMM_WORLD);
}

void barrier() { MPI_Barrier(PETSC_COMM_WORLD); }

void abort_ranks(int code) {
  PetscBool started = PETSC_FALSE;
  PetscInitialized(&started);
  if (started) MPI_Abort(PETSC_COMM_WORLD, code);
}

}  // namespace perinom::detail
