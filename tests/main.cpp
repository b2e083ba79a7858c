// Catch2's runner, then PETSc's end (and MPI's) when a test started it.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include "perinom/solvers/petsc.hpp"

int main(int argc, char** argv) {
  const int result = Catch::Session().run(argc, argv);
  perinom::finalize_petsc();
  return result;
}
