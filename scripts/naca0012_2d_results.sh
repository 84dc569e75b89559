#!/usr/bin/env bash
# Reproduces docs/naca0012_2d/: the demo's table with the largest amplitudes,
# the JSON reports, and the figures. Run from the repository root after a build.
set -euo pipefail
cd "$(dirname "$0")/.."
out=docs/naca0012_2d
mkdir -p "$out/reports"
./build/examples/naca0012_pitch_2d --max-amplitude --report-dir "$out/reports" | tee "$out/table.txt"
./build/examples/naca0012_pitch_2d --solver paper --max-amplitude --report-dir "$out/reports_paper_solver" \
  | tee "$out/table_paper_solver.txt"
/usr/bin/python3 scripts/validate_report.py "$out"/reports/*_pos.json "$out"/reports/*_neg.json \
  "$out"/reports_paper_solver/*_pos.json "$out"/reports_paper_solver/*_neg.json
/usr/bin/python3 scripts/make_figures_2d.py "$out/reports" docs/figures
# VTU files are large and reproducible: keep only the JSON reports in git
rm -f "$out"/reports/*.vtu "$out"/reports_paper_solver/*.vtu
