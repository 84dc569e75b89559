#!/usr/bin/env bash
# Largest pitch amplitude of every model on the 2D NACA0012 case (coarse
# mesh, 100 steps, bisection to 0.5 deg up to 180), without adaptive
# substepping (the paper's method) and with up to 2^K substeps per step.
#
#   scripts/substepping_amplitudes.sh [BUILD_DIR] [K]
#
# BUILD_DIR (default build-rel) must hold examples/naca0012_pitch_2d;
# K defaults to 6 (64 substeps). Writes docs/reliability/:
#   substepping_k0.txt, substepping_kK.txt   the program's full output
#   substepping_k0.json, substepping_kK.json its max_amplitude reports
#   substepping_amplitudes.txt               the comparison table
#   substepping_amplitudes.png               the figure
# Runs many solves (minutes): run it with nice on a shared machine.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$here/build-rel}"
k="${2:-6}"
exe="$build/examples/naca0012_pitch_2d"
out="$here/docs/reliability"
[ -x "$exe" ] || { echo "substepping_amplitudes.sh: no $exe (build the naca0012_pitch_2d target)" >&2; exit 2; }
mkdir -p "$out"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
for h in 0 "$k"; do
  mkdir -p "$tmp/k$h"
  "$exe" --max-amplitude --max-substep-halvings "$h" --report-dir "$tmp/k$h" > "$tmp/k$h.txt"
  cp "$tmp/k$h.txt" "$out/substepping_k$h.txt"
  cp "$tmp/k$h/max_amplitude.json" "$out/substepping_k$h.json"
done
/usr/bin/python3 "$here/scripts/plot_substepping_amplitudes.py" "$out/substepping_k0.json" "$out/substepping_k$k.json" \
  "$k" "$out/substepping_amplitudes.txt" "$out/substepping_amplitudes.png"
cat "$out/substepping_amplitudes.txt"
