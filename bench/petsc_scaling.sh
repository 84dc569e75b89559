#!/usr/bin/env bash
# Copyright (c) 2026 SpringMotion developers.
# Strong scaling of the PETSc backend on this machine (docs/scaling.md): the
# Gmsh wing (scripts/make_gmsh_wing.py, made into BUILD/gmsh_wing/wing.msh if
# missing), STEPS steps of grid-scaled springs to 10 degrees, run with the
# shared backend (1 thread, then the default) and with --backend petsc on 1
# and 2 MPI ranks (one thread each). Prints wall time (whole process), the
# stiffness and solve times and the solver iterations from each run's report
# (rank 0's part on PETSc), the run's peak memory (its largest process) and
# on PETSc each rank's, and the final state's worst R and smallest dihedral
# angle (which must agree between the runs). With BOX_N, the same
# four runs on the structured box with a hole of scripts/make_box_mesh.py
# (BOX_N = 100: about a million vertices), 2 steps to 1 degree.
#   bench/petsc_scaling.sh BUILD_PETSC [STEPS [BOX_N]]     (BUILD_PETSC: a build with SPRING_MOTION_WITH_PETSC=ON)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:?usage: bench/petsc_scaling.sh BUILD_PETSC [STEPS]}
steps=${2:-10}
box=${3:-}
cli="$build/src/cli/spring-motion"
mesh="$build/gmsh_wing/wing.msh"
[ -f "$mesh" ] || { mkdir -p "$(dirname "$mesh")"; /usr/bin/python3 scripts/make_gmsh_wing.py "$mesh"; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
args=(deform "$mesh" --moving wing --pitch 10 --center 0.5,0,0 --axis 0,0,1 --steps "$steps" --quiet)
echo "uptime before: $(uptime)"
printf '%-28s %8s %11s %8s %11s %9s %8s %8s %s\n' "run" "wall s" "stiffness s" "solve s" "iterations" "peak MiB" "worst R" "min deg" "MiB per rank"
# peak MiB: the largest resident set of the run's processes (getrusage of
# the children: under mpiexec, the largest rank)
run() {
  local name=$1; shift
  /usr/bin/python3 - "$name" "$work/r.json" "$@" <<'PY'
import json, resource, subprocess, sys, time
name, path, cmd = sys.argv[1], sys.argv[2], sys.argv[3:]
t0 = time.monotonic()
subprocess.run(cmd + ["--report", path], check=True, stdout=subprocess.DEVNULL)
wall = time.monotonic() - t0
peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
r = json.load(open(path))
stiffness = sum(s["seconds"]["stiffness"] for s in r["steps"])
solve = sum(s["seconds"]["solve"] for s in r["steps"])
its = sum(s["iterations"] for s in r["steps"])
q = r["quality"]  # the final state: the largest R and the smallest dihedral angle over all tetrahedra
ranks = r["backend"].get("peak_mib_per_rank", [])
print("%-28s %8.2f %11.2f %8.2f %11d %9.0f %8.4f %8.3f %s"
      % (name, wall, stiffness, solve, its, peak, q["all"]["max"], q["all"]["min_angle_deg"],
         " ".join("%.0f" % m for m in ranks)))
PY
}
four_runs() {
  run "shared, 1 thread" "$cli" "${args[@]}" --threads 1
  run "shared, default threads" "$cli" "${args[@]}"
  run "petsc, 1 rank" env OMP_NUM_THREADS=1 "$cli" "${args[@]}" --threads 1 --backend petsc
  run "petsc, 2 ranks" mpiexec -n 2 --oversubscribe env OMP_NUM_THREADS=1 "$cli" "${args[@]}" --threads 1 --backend petsc
}
echo "Gmsh wing, $steps steps of grid_scaled springs to 10 degrees"
four_runs
if [ -n "$box" ]; then
  /usr/bin/python3 scripts/make_box_mesh.py "$box" "$work/box.mesh"
  args=(deform "$work/box.mesh" --moving 1 --pitch 1 --center 0.5,0.5,0.5 --steps 2 --quiet)
  echo "box with a hole, $box^3 cubes, 2 steps of grid_scaled springs to 1 degree"
  four_runs
fi
echo "uptime after: $(uptime)"
