#!/usr/bin/env bash
# Reproduces docs/naca0012_3d/: the wing demo's table (with the largest
# amplitudes unless NO_MAX_AMPLITUDE=1), the JSON reports, and the figures.
# Run from the repository root after building the target naca0012_wing_3d in
# BUILD (default: build). The VTU files (about 50 MB each) stay in BUILD.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
out=docs/naca0012_3d
work="$build/naca0012_3d_reports"
mkdir -p "$out/reports" "$work"
max=(--max-amplitude)
[ "${NO_MAX_AMPLITUDE:-0}" = 1 ] && max=()
nice "$build/examples/naca0012_wing_3d" "${max[@]}" --report-dir "$work" | tee "$out/table.txt"
cp "$work"/*.json "$out/reports/"
/usr/bin/python3 scripts/validate_report.py "$out"/reports/*_pos.json "$out"/reports/*_neg.json
/usr/bin/python3 scripts/make_figures_3d.py "$work" docs/figures
