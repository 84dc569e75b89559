#!/bin/bash
# Copyright (c) 2026 SpringMotion developers.
# The half-span wing on its symmetry plane (docs/half_wing/): the Gmsh half
# wing of scripts/make_gmsh_wing.py --half pitched to 30 degrees about the
# spanwise axis through (0.5, 0, 0), with the plane z = 0 sliding and, for
# comparison, held fixed, for the paper's grid-scaled springs and the
# ball-vertex springs with k = 1/h^2. Writes docs/half_wing/results.txt and
# the figure docs/half_wing/symmetry_plane.png (ball-vertex springs).
#
#   scripts/half_wing_results.sh [BUILD_DIR]     (default: build; about 5 minutes)
set -euo pipefail
build=${1:-build}
cli="$build/src/cli/spring-motion"
work="$build/half_wing"
out=docs/half_wing
mkdir -p "$work" "$out"
mesh="$work/half_wing.msh"
[ -f "$mesh" ] || /usr/bin/python3 scripts/make_gmsh_wing.py "$mesh" --half

{
  echo "# scripts/half_wing_results.sh on $(date -u +%Y-%m-%d), $(nproc) cores; uptime before the runs:"
  uptime
  for model in grid_scaled ball_vertex_p2; do
    for plane in sliding fixed; do
      extra=()
      [ "$plane" = sliding ] && extra=(--sliding symmetry)
      printf '%-15s plane %-8s ' "$model" "$plane"
      # exit status 3 (a step inverted an element) is a result here, not a failure
      "$cli" deform "$mesh" --moving wing "${extra[@]}" --pitch 30 --center 0.5,0,0 --axis 0,0,1 --steps 100 \
        --model "$model" --report "$work/${model}_$plane.json" --output "$work/${model}_$plane.msh" \
        2>/dev/null | tail -n 1 || [ "${PIPESTATUS[0]}" -eq 3 ]
    done
  done
  echo
  /usr/bin/python3 scripts/plot_symmetry_plane.py --table "$mesh" "$work"/*_sliding.msh "$work"/*_fixed.msh
} > "$out/results.txt.tmp"
mv "$out/results.txt.tmp" "$out/results.txt"
/usr/bin/python3 scripts/plot_symmetry_plane.py --figure "$out/symmetry_plane.png" "$mesh" \
  "$work/ball_vertex_p2_sliding.msh" "$work/ball_vertex_p2_fixed.msh"
cat "$out/results.txt"
