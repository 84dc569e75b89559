#!/usr/bin/env bash
# Reproduces docs/element_models/: the element models (ball-vertex springs with
# k = 1/h and 1/h^2, torsional springs) against the paper's grid-scaled springs
# at large pitch angles, in 2D (the paper's airfoil) and 3D (the Mesh_3 wing of
# the wing demo and an independent Gmsh wing).
#
#   scripts/element_models_results.sh [BUILD_DIR] [2d|wing|gmsh ...]
#
# BUILD_DIR (default build) must hold examples/naca0012_pitch_2d,
# examples/naca0012_wing_3d and the spring-motion command; the Gmsh wing
# needs Debian's python3-gmsh. Without parts, runs all three. The 3D runs
# pitch to +/-90 degrees; on the Gmsh wing the smallest dihedral angle at 30
# degrees is read from their step reports (scripts/angle_at_30.py: the first
# step at or past 30 degrees, 30.5 with 100 quarter-sine steps to 90), the
# wing demo runs to 30 degrees as well. The 3D parts take
# about an hour on a busy 2-core machine (100 steps of a 55000-node wing, a
# second or so each, per model and direction); each table is written under
# another name and renamed when complete.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
shift || true
parts=("$@")
[ ${#parts[@]} -eq 0 ] && parts=(2d wing gmsh)
out=docs/element_models
mkdir -p "$out"
models3d=ball_vertex,ball_vertex_p2,torsional

finish() { mv "$1.tmp" "$1"; echo "wrote $1"; }

for part in "${parts[@]}"; do
  case "$part" in
  2d)
    exe="$build/examples/naca0012_pitch_2d"
    { uptime
      "$exe" --models grid_scaled,ball_vertex,ball_vertex_p2,torsional --amplitude 45
      "$exe" --models ball_vertex,ball_vertex_p2,torsional --amplitude 360
      "$exe" --models ball_vertex_p2,torsional --amplitude 720
    } > "$out/naca0012_2d.txt.tmp"
    finish "$out/naca0012_2d.txt"
    ;;
  wing)
    exe="$build/examples/naca0012_wing_3d"
    { uptime
      # the demo skips the per-step quality (its ms/step column times the
      # motion alone), so the angles at 30 degrees come from runs to 30
      # the Mesh_3 wing these tables were made on: the demo's first default
      # (Mesh_3 alone), not today's ODT + sliver-pass default
      for a in 90 30; do
        mkdir -p "$build/element_models/wing_$a"
        nice "$exe" --mesh-cache "$build" --odt 0 --sliver-bound 10 --sliver-smoothing 0 \
          --models "$models3d" --amplitude "$a" \
          --report-dir "$build/element_models/wing_$a"
      done
    } > "$out/naca0012_wing_3d.txt.tmp"
    finish "$out/naca0012_wing_3d.txt"
    ;;
  gmsh)
    mesh="$build/gmsh_wing/wing.msh"
    mkdir -p "$build/gmsh_wing"
    [ -f "$mesh" ] || /usr/bin/python3 scripts/make_gmsh_wing.py "$mesh"
    { uptime
      for m in ${models3d//,/ }; do
        for a in 90 -90; do
          printf '%-16s %4s deg: ' "$m" "$a"
          # exit status 3 (a step inverted an element) is a result here, not a failure
          nice "$build/src/cli/spring-motion" deform "$mesh" --moving wing --pitch "$a" --center 0.5,0,0 \
            --axis 0,0,1 --steps 100 --model "$m" --quiet --report "$build/gmsh_wing/${m}_$a.json" || [ $? -eq 3 ]
        done
      done
      echo
      /usr/bin/python3 scripts/angle_at_30.py "$build"/gmsh_wing/*_90.json "$build"/gmsh_wing/*_-90.json
    } > "$out/gmsh_wing.txt.tmp"
    finish "$out/gmsh_wing.txt"
    ;;
  *)
    echo "element_models_results.sh: unknown part '$part' (2d, wing or gmsh)" >&2
    exit 2
    ;;
  esac
done
