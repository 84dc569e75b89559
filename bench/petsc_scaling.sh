#!/usr/bin/env bash
# Copyright (c) 2026 SpringMotion developers.
# Strong scaling of the PETSc backend on this machine (docs/scaling.md): the
# Gmsh wing (scripts/make_gmsh_wing.py, made into BUILD/gmsh_wing/wing.msh if
# missing), STEPS steps of grid-scaled springs to 10 degrees, run with the
# shared backend (1 thread, then the default) and with --backend petsc on 1
# and 2 MPI ranks (one thread each). Prints wall time (whole process), the
# solve time and the solver iterations from each run's report.
#   bench/petsc_scaling.sh BUILD_PETSC [STEPS]     (BUILD_PETSC: a build with SPRING_MOTION_WITH_PETSC=ON)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:?usage: bench/petsc_scaling.sh BUILD_PETSC [STEPS]}
steps=${2:-10}
cli="$build/src/cli/spring-motion"
mesh="$build/gmsh_wing/wing.msh"
[ -f "$mesh" ] || { mkdir -p "$(dirname "$mesh")"; /usr/bin/python3 scripts/make_gmsh_wing.py "$mesh"; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
args=(deform "$mesh" --moving wing --pitch 10 --center 0.5,0,0 --axis 0,0,1 --steps "$steps" --quiet)
echo "uptime before: $(uptime)"
printf '%-28s %10s %10s %11s\n' "run" "wall s" "solve s" "iterations"
run() {
  local name=$1; shift
  local t0 t1
  t0=$(date +%s.%N)
  "$@" --report "$work/r.json" > /dev/null
  t1=$(date +%s.%N)
  /usr/bin/python3 - "$name" "$t0" "$t1" "$work/r.json" <<'PY'
import json, sys
name, t0, t1, path = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), sys.argv[4]
r = json.load(open(path))
solve = sum(s["seconds"]["solve"] for s in r["steps"])
its = sum(s["iterations"] for s in r["steps"])
print("%-28s %10.2f %10.2f %11d" % (name, t1 - t0, solve, its))
PY
}
run "shared, 1 thread" "$cli" "${args[@]}" --threads 1
run "shared, default threads" "$cli" "${args[@]}"
run "petsc, 1 rank" env OMP_NUM_THREADS=1 "$cli" "${args[@]}" --threads 1 --backend petsc
run "petsc, 2 ranks" mpiexec -n 2 --oversubscribe env OMP_NUM_THREADS=1 "$cli" "${args[@]}" --threads 1 --backend petsc
echo "uptime after: $(uptime)"
