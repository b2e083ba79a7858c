// The program with PETSc: options passed through to the solver, and mpirun refused for the
// commands that are not distributed (each rank would do the whole work).
#include <cstdlib>

#include "../support/cli.hpp"

// (No perinom header here: namespace perinom and cli_test::perinom would clash.)

using namespace cli_test;

TEST_CASE("PETSc options from the command line reach the Newton solve", "[cli][petsc]") {
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << with(tiny_scene, "  type: adr\n", "  type: newton\n  linear_solver: gamg\n");
  const Outcome o = perinom(dir, "run scene.yaml --petsc-options '-snes_monitor -ksp_converged_reason'");
  INFO("stdout: " << o.out << "\nstderr: " << o.err);
  if (o.err.find("built without PETSc") != std::string::npos) {  // a build without it refuses by name
    CHECK(o.exit_code == 2);
    return;
  }
  CHECK(o.exit_code == 0);
  CHECK(o.out.find("SNES Function norm") != std::string::npos);
  CHECK(o.out.find("Linear solve converged") != std::string::npos);
  // A wrong option value is PETSc's to reject: the run stops with the solve failed (exit 3).
  const Outcome bad = perinom(dir, "run scene.yaml --petsc-options '-ksp_type no_such_method'");
  INFO("stderr: " << bad.err);
  CHECK(bad.exit_code == 3);
  CHECK(bad.err.find("no_such_method") != std::string::npos);
}

TEST_CASE("more than one MPI rank is refused with a clear message", "[cli][petsc]") {
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << tiny_scene;
  // What mpirun -np 2 puts into each rank's environment (Open MPI; MPICH sets PMI_SIZE); check
  // is not distributed (run is: the mpi.run_* tests run it under mpirun).
  setenv("OMPI_COMM_WORLD_SIZE", "2", 1);
  const Outcome o = perinom(dir, "check scene.yaml");
  unsetenv("OMPI_COMM_WORLD_SIZE");
  require_one_clear_error(o, {"one MPI rank", "mpirun -np 2"});
}

TEST_CASE("a SNES solve that stops leaves the last good state, not its iterate", "[cli][petsc]") {
  // A 3-D box free along z: MUMPS finds no null pivot in rounding, the line search fails, and
  // the state written was the iterate SNES stopped at (a tip 1.3e8 m off).
  ScratchDir dir;
  const Outcome o = perinom(dir, "run '" PERINOM_SOURCE_DIR "/tests/data/distributed_box.yaml' --out out "
                                 "--set \"boundary.0.fix=[x, y]\" --set solver.type=newton --set solver.linear_solver=mumps");
  INFO("stdout: " << o.out << "\nstderr: " << o.err);
  if (o.err.find("mumps needs PETSc") != std::string::npos) {  // a build without it refuses by name
    CHECK(o.exit_code == 2);
    return;
  }
  if (o.err.find("null pivots") != std::string::npos) return;  // (another BLAS's rounding: MUMPS names it, exit 2)
  CHECK(o.exit_code == 3);
  CHECK(o.err.find("the last good state is load step 0") != std::string::npos);
  CHECK(json_number(slurp(dir.path / "out" / "summary.json"), "tip_uz") == 0.0);
}
