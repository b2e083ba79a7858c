#!/usr/bin/env bash
# Installs perinom's build and test dependencies from Debian packages (run as root).
set -euo pipefail
# libopenblas0-pthread: an optimized BLAS behind libblas.so.3 for CHOLMOD's supernodal
# Cholesky (solver.type direct, the stability check) and UMFPACK's frontal matrices (Newton);
# the reference BLAS gives the same answers, 2.3 times slower on the 3-D cantilever at 8
# particles through the thickness (direct).
# petsc-dev and openmpi-bin: Newton through PETSc (solver.linear_solver mumps | gamg; PETSc
# 3.18 with MUMPS and hypre), found by CMake through pkg-config; the library builds without
# them and then refuses those solvers by name.
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends \
  g++ cmake make pkg-config \
  libeigen3-dev libsuitesparse-dev libsundials-dev catch2 libvtk9-dev \
  libyaml-cpp-dev libnanoflann-dev libopenblas0-pthread \
  petsc-dev openmpi-bin \
  python3 python3-numpy python3-matplotlib >/dev/null
echo "perinom: dependencies installed"
