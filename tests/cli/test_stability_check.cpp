// The stability check as a user meets it: `perinom check --spectrum` and the warning of a
// static run with a non-symmetric formulation, on the vibrating bar of the examples. Each
// test runs the real binary in its own temporary folder.
#include <catch2/catch.hpp>

#include "../support/bar_run.hpp"
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>

namespace fs = std::filesystem;

namespace {

using bar_test::bar;
using bar_test::Outcome;

}  // namespace

TEST_CASE("perinom check --spectrum finds the improved formulation unstable and consistent stable", "[cli][spectrum]") {
  const Outcome improved = bar("check_improved", "check --spectrum", "--set discretization.dx=0.002 --set model.formulation=improved --set solver.type=adr");
  INFO(improved.out << improved.err);
  REQUIRE(improved.exit_code == 0);
  CHECK(improved.out.find("eigenvalues of M^-1 K on 490 free dofs") != std::string::npos);
  CHECK(improved.out.find("growth rate") != std::string::npos);
  CHECK(improved.out.find("\n  UNSTABLE: ") != std::string::npos);
  const Outcome consistent = bar("check_consistent", "check --spectrum", "--set discretization.dx=0.002 --set model.formulation=consistent --set solver.type=adr");
  INFO(consistent.out << consistent.err);
  REQUIRE(consistent.exit_code == 0);
  CHECK(consistent.out.find("\n  stable\n") != std::string::npos);
  CHECK(consistent.out.find("UNSTABLE") == std::string::npos);
}

TEST_CASE("perinom check --spectrum checks a large symmetric scene sparsely and refuses a large non-symmetric one",
          "[cli][spectrum]") {
  // dx 0.5 mm: 200 x 20 particles, 7,960 free dofs: the consistent formulation's K is
  // symmetric (its inertia decides), the improved one's is not (the dense solve, limited).
  const Outcome consistent = bar("check_large", "check --spectrum", "--set discretization.dx=0.0005");
  INFO(consistent.out << consistent.err);
  CHECK(consistent.exit_code == 0);
  CHECK(consistent.out.find("on 7960 free dofs (Galerkin reduction, sparse Cholesky: positive definite") != std::string::npos);
  CHECK(consistent.out.find("\n  stable\n") != std::string::npos);
  const Outcome improved = bar("check_large_improved", "check --spectrum",
                               "--set discretization.dx=0.0005 --set model.formulation=improved --set solver.type=adr");
  INFO(improved.out << improved.err);
  CHECK(improved.exit_code == 2);
  CHECK(improved.err.find("7960 free degrees of freedom of a non-symmetric stiffness") != std::string::npos);
  CHECK(improved.err.find("above the dense limit of 2000") != std::string::npos);
}

TEST_CASE("a static run with the improved formulation warns when the check finds it unstable", "[cli][spectrum]") {
  const Outcome o = bar("run_improved", "run", "--out out --set discretization.dx=0.002 --set model.formulation=improved "
                        "--set solver.type=newton");
  INFO(o.out << o.err);
  CHECK(o.exit_code == 0);
  CHECK(o.out.find("warning: model.formulation improved: the discrete problem is unstable (") != std::string::npos);
  CHECK(o.out.find("use consistent") != std::string::npos);
  // Symmetric formulations are not checked and not warned about.
  const Outcome c = bar("run_consistent", "run", "--out out --set discretization.dx=0.002 --set solver.type=newton");
  INFO(c.out << c.err);
  CHECK(c.exit_code == 0);
  CHECK(c.err.empty());
  CHECK(c.out.find("warning") == std::string::npos);
}

TEST_CASE("a static run with the strong formulation above the size limit says the check was skipped", "[cli][spectrum]") {
  // ADR stopped after 10 iterations (exit 1): the warning comes before the solve.
  const Outcome o = bar("run_large", "run", "--out out --set discretization.dx=0.0005 --set model.formulation=strong "
                        "--set solver.type=adr --set solver.max_iterations=10");
  INFO(o.out << o.err);
  CHECK(o.exit_code == 1);
  CHECK(o.out.find("warning: model.formulation strong: non-symmetric") != std::string::npos);
  CHECK(o.out.find("the stability check was skipped: 7960 free dofs exceed its limit of 2000") != std::string::npos);
  CHECK(o.err.empty());  // (ADR's NOT converged line is on stdout)
}

TEST_CASE("a body the supports leave free is singular in the stability check, not unstable", "[cli][stability]") {
  // Its rigid modes' pivots are rounding of either sign: it read "2 negative" and UNSTABLE
  // beside a positive smallest eigenvalue.
  const Outcome o = bar("free_spectrum", "check",
                        "--spectrum --set discretization.dx=0.004 --set \"boundary=[{region: left, traction: [-1.0e6, 0.0]}, "
                        "{region: right, traction: [1.0e6, 0.0]}]\"");
  INFO("stdout: " << o.out << "\nstderr: " << o.err);
  REQUIRE(o.exit_code == 0);
  CHECK(o.out.find("negative                    0 (negative pivots of K; 3 zero)") != std::string::npos);
  CHECK(o.out.find("stable but singular: 3 zero eigenvalues") != std::string::npos);
  CHECK(o.out.find("UNSTABLE") == std::string::npos);
}
