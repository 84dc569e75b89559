#!/usr/bin/env bash
# Installs the Debian 12 packages SpringMotion needs to build, test and make
# its figures. Uses sudo when not run as root.
# Opt-in: `--petsc` (or SPRING_MOTION_WITH_PETSC=1 in the environment) also
# installs PETSc and MPI for the optional backend (CMake option
# SPRING_MOTION_WITH_PETSC); the default install does not change.
set -euo pipefail
WITH_PETSC="${SPRING_MOTION_WITH_PETSC:-0}"
for arg in "$@"; do
  case "$arg" in
    --petsc) WITH_PETSC=1 ;;
    *) echo "usage: $0 [--petsc]" >&2; exit 2 ;;
  esac
done
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
# nlohmann-json3-dev: writes the JSON report (src/report_json.cpp) and reads it
# back in the tests; libcli11-dev: parses the spring-motion command line.
# Both are header-only.
# pybind11-dev, python3-dev: the Python module (python/); python3-pytest runs
# its tests; python3-setuptools, -wheel, -pip, -venv: `pip install
# --no-build-isolation .` with Debian's own build tools (nothing is fetched).
# python3-gmsh: the Gmsh wing script (scripts/make_gmsh_wing.py) and the
# binary test meshes' generator.
$SUDO apt-get install -y -q --no-install-recommends \
  g++ make cmake \
  libcgal-dev libboost-graph-dev libeigen3-dev catch2 \
  nlohmann-json3-dev libcli11-dev \
  pybind11-dev python3-dev python3-pytest python3-setuptools python3-wheel python3-pip python3-venv \
  python3 python3-numpy python3-matplotlib python3-meshio python3-gmsh
if [ "$WITH_PETSC" = "1" ]; then
  # libpetsc-real-dev: PETSc 3.18 (KSP, GAMG, MPIAIJ matrices) with its
  # pkg-config file; mpi-default-dev/-bin: OpenMPI headers, mpicc and mpirun.
  $SUDO apt-get install -y -q --no-install-recommends \
    libpetsc-real-dev mpi-default-dev mpi-default-bin pkg-config
fi
