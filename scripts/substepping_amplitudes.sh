#!/usr/bin/env bash
# Largest pitch amplitude of every model on the 2D NACA0012 case (coarse
# mesh, bisection to 0.5 deg up to 180), without adaptive substepping (the
# paper's method) and with up to 2^K substeps per step, for each step count.
#
#   scripts/substepping_amplitudes.sh [BUILD_DIR] [K] [STEPS...]
#
# BUILD_DIR (relative to the repository root, default build: the folder the
# README's commands make) must hold examples/naca0012_pitch_2d;
# K defaults to 6 (64 substeps), STEPS to "100 10". Writes docs/reliability/:
#   substepping_n<STEPS>_k<0|K>.txt    the program's full output
#   substepping_n<STEPS>_k<0|K>.json   its max_amplitude report
#   substepping_amplitudes.txt         the comparison table
#   substepping_amplitudes.png         the figure
# Runs many solves (tens of minutes on a busy machine): use nice.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
cd "$here"
build="${1:-build}"
k="${2:-6}"
shift $(( $# < 2 ? $# : 2 ))
steps=("$@")
[ ${#steps[@]} -gt 0 ] || steps=(100 10)
exe="$build/examples/naca0012_pitch_2d"
out="$here/docs/reliability"
[ -x "$exe" ] || { echo "substepping_amplitudes.sh: no $exe (build the naca0012_pitch_2d target)" >&2; exit 2; }
mkdir -p "$out"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
jsons=()
for n in "${steps[@]}"; do
  for h in 0 "$k"; do
    name="substepping_n${n}_k${h}"
    mkdir -p "$tmp/$name"
    "$exe" --steps "$n" --max-amplitude --max-substep-halvings "$h" --report-dir "$tmp/$name" > "$tmp/$name.txt"
    cp "$tmp/$name.txt" "$out/$name.txt"
    cp "$tmp/$name/max_amplitude.json" "$out/$name.json"
    jsons+=("$out/$name.json")
  done
done
/usr/bin/python3 "$here/scripts/plot_substepping_amplitudes.py" "$k" "$out/substepping_amplitudes.txt" \
  "$out/substepping_amplitudes.png" "${jsons[@]}"
cat "$out/substepping_amplitudes.txt"
