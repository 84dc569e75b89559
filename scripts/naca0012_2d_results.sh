#!/usr/bin/env bash
# Reproduces docs/naca0012_2d/: the demo's table with the largest amplitudes,
# the JSON reports, and the figures.
#
#   scripts/naca0012_2d_results.sh [BUILD_DIR]
#
# BUILD_DIR (relative to the repository root, default build: the folder the
# README's commands make) must hold examples/naca0012_pitch_2d.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
exe="$build/examples/naca0012_pitch_2d"
[ -x "$exe" ] || { echo "naca0012_2d_results.sh: no $exe (build the naca0012_pitch_2d target)" >&2; exit 2; }
out=docs/naca0012_2d
mkdir -p "$out/reports"
"$exe" --max-amplitude --report-dir "$out/reports" | tee "$out/table.txt"
"$exe" --solver paper --max-amplitude --report-dir "$out/reports_paper_solver" \
  | tee "$out/table_paper_solver.txt"
/usr/bin/python3 scripts/validate_report.py "$out"/reports/*_pos.json "$out"/reports/*_neg.json \
  "$out"/reports_paper_solver/*_pos.json "$out"/reports_paper_solver/*_neg.json
/usr/bin/python3 scripts/make_figures_2d.py "$out/reports" docs/figures
# VTU files are large and reproducible: keep only the JSON reports in git
rm -f "$out"/reports/*.vtu "$out"/reports_paper_solver/*.vtu
