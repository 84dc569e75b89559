#!/usr/bin/env bash
# Builds and tests the optional PETSc backend in its own build directory
# (build-petsc, CMake option SPRING_MOTION_WITH_PETSC=ON): installs the opt-in
# packages (PETSc, OpenMPI), builds only the PETSc test targets and runs the
# tests labelled "petsc" (on 1 and 2 ranks). Set SKIP_INSTALL=1 to skip apt.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "${SKIP_INSTALL:-0}" != "1" ]; then
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends \
    libpetsc-real-dev mpi-default-dev mpi-default-bin pkg-config
fi
JOBS="${JOBS:-2}"
cmake -S . -B build-petsc -DCMAKE_BUILD_TYPE=Release -DSPRING_MOTION_WITH_PETSC=ON \
  -DSPRING_MOTION_BUILD_EXAMPLES=OFF -DSPRING_MOTION_WARNINGS_AS_ERRORS=ON
cmake --build build-petsc --target petsc_toolchain petsc_step_system spring-motion -j"$JOBS"
ctest --test-dir build-petsc -L petsc --output-on-failure
