#!/usr/bin/env bash
# Reproduces docs/naca0012_3d/: the wing demo's table (with the largest
# amplitudes unless NO_MAX_AMPLITUDE=1), the JSON reports, and the figures.
#
#   [NO_MAX_AMPLITUDE=1] scripts/naca0012_3d_results.sh [BUILD_DIR]
#
# BUILD_DIR (relative to the repository root, default build: the folder the
# README's commands make) must hold examples/naca0012_wing_3d; the wing mesh
# is cached there, and the VTU files (about 50 MB each) stay there.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
exe="$build/examples/naca0012_wing_3d"
[ -x "$exe" ] || { echo "naca0012_3d_results.sh: no $exe (build the naca0012_wing_3d target)" >&2; exit 2; }
out=docs/naca0012_3d
work="$build/naca0012_3d_reports"
mkdir -p "$out/reports" "$work"
max=(--max-amplitude)
[ "${NO_MAX_AMPLITUDE:-0}" = 1 ] && max=()
nice "$exe" "${max[@]}" --mesh-cache "$build" --report-dir "$work" | tee "$out/table.txt"
cp "$work"/*.json "$out/reports/"
/usr/bin/python3 scripts/validate_report.py "$out"/reports/*_pos.json "$out"/reports/*_neg.json
/usr/bin/python3 scripts/make_figures_3d.py "$work" docs/figures
