// PT-Scotch on the bond graph through PETSc (petsc_partition.hpp).
#include "petsc_partition.hpp"

#include <petscmat.h>

#include <limits>
#include <string>

#include "perinom/core/error.hpp"
#include "petsc_session.hpp"

namespace perinom::detail {

void partition_graph(std::size_t n, const std::int64_t* offsets, const std::int32_t* cols, int parts, int* rank_of) {
  start_petsc("");
  const std::int64_t edges = offsets[n];
  if (n > static_cast<std::size_t>(std::numeric_limits<PetscInt>::max()) ||
      edges > static_cast<std::int64_t>(std::numeric_limits<PetscInt>::max()))
    throw InputError("PT-Scotch partition: " + std::to_string(edges) + " bond-graph edges, more than PETSc's index type holds");
  // MatCreateMPIAdj takes the arrays, allocated by PETSc, and frees them with the matrix.
  PetscInt *ia = nullptr, *ja = nullptr;
  check(PetscMalloc1(n + 1, &ia), "PetscMalloc1");
  check(PetscMalloc1(edges > 0 ? edges : 1, &ja), "PetscMalloc1");
  for (std::size_t i = 0; i <= n; ++i) ia[i] = static_cast<PetscInt>(offsets[i]);
  for (std::int64_t k = 0; k < edges; ++k) ja[k] = static_cast<PetscInt>(cols[k]);
  Mat adj = nullptr;
  MatPartitioning part = nullptr;
  IS is = nullptr;
  const PetscInt m = static_cast<PetscInt>(n);
  check(MatCreateMPIAdj(PETSC_COMM_SELF, m, m, ia, ja, nullptr, &adj), "MatCreateMPIAdj");
  try {
    check(MatPartitioningCreate(PETSC_COMM_SELF, &part), "MatPartitioningCreate");
    check(MatPartitioningSetAdjacency(part, adj), "MatPartitioningSetAdjacency");
    check(MatPartitioningSetType(part, MATPARTITIONINGPTSCOTCH), "MatPartitioningSetType(ptscotch)");
    check(MatPartitioningSetNParts(part, parts), "MatPartitioningSetNParts");
    check(MatPartitioningApply(part, &is), "MatPartitioningApply");
    const PetscInt* idx = nullptr;
    check(ISGetIndices(is, &idx), "ISGetIndices");
    for (std::size_t i = 0; i < n; ++i) rank_of[i] = static_cast<int>(idx[i]);
    ISRestoreIndices(is, &idx);
  } catch (...) {
    ISDestroy(&is);
    MatPartitioningDestroy(&part);
    MatDestroy(&adj);
    throw;
  }
  ISDestroy(&is);
  MatPartitioningDestroy(&part);
  MatDestroy(&adj);
}

}  // namespace perinom::detail
