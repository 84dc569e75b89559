#!/usr/bin/python3
"""Validates SpringMotion JSON reports against docs/report_format.md
("spring_motion.report/1"). Usage: validate_report.py FILE...
Exits non-zero, naming the file and the field, on the first violation."""
import json
import math
import sys


def fail(path, what):
    sys.exit(f"{path}: {what}")


def check_number(path, name, v, nullable=False):
    if v is None and nullable:
        return
    if not isinstance(v, (int, float)) or isinstance(v, bool) or not math.isfinite(v):
        fail(path, f"{name} should be a finite number, got {v!r}")


def check_histogram(path, name, q):
    for k in ("histogram", "count", "mean", "max"):
        if k not in q:
            fail(path, f"{name}.{k} missing")
    h = q["histogram"]
    if len(h) != 10:
        fail(path, f"{name}.histogram has {len(h)} bins, expected 10")
    for f in h:
        check_number(path, f"{name}.histogram[]", f)
        if f < 0 or f > 1:
            fail(path, f"{name}.histogram fraction {f} outside [0, 1]")
    if q["count"] > 0 and abs(sum(h) - 1) > 1e-9:
        fail(path, f"{name}.histogram sums to {sum(h)}, expected 1")
    if q["count"] > 0 and not (0 <= q["mean"] <= q["max"] <= 1):
        fail(path, f"{name}: expected 0 <= mean <= max <= 1")


def validate(path):
    with open(path) as f:
        r = json.load(f)
    if r.get("format") != "spring_motion.report/1":
        fail(path, f"format is {r.get('format')!r}, expected 'spring_motion.report/1'")
    for k in ("mesh", "model", "motion", "solver", "steps", "completed", "first_invalid", "final_angle_deg",
              "quality", "seconds_total"):
        if k not in r:
            fail(path, f"field '{k}' missing")
    m = r["mesh"]
    for k in ("dimension", "vertices", "elements", "moving_vertices", "fixed_vertices"):
        if not isinstance(m.get(k), int):
            fail(path, f"mesh.{k} should be an integer")
    # written since sliding boundaries exist; older reports lack it (0)
    if not isinstance(m.get("sliding_vertices", 0), int):
        fail(path, "mesh.sliding_vertices should be an integer")
    if m["dimension"] not in (2, 3):
        fail(path, "mesh.dimension should be 2 or 3")
    if not isinstance(r["model"].get("name"), str) or not isinstance(r["model"].get("parameters"), dict):
        fail(path, "model needs a name and a parameters object")
    mo = r["motion"]
    for k in ("kind", "steps", "center", "axis"):
        if k not in mo:
            fail(path, f"motion.{k} missing")
    if len(mo["center"]) != 3 or len(mo["axis"]) != 3:
        fail(path, "motion.center and motion.axis need 3 components")
    so = r["solver"]
    choices = {"name": ("conjugate_gradient", "sor"),
               "preconditioner": ("multigrid", "symmetric_gauss_seidel", "none"),
               "stopping": ("error_estimate", "max_update"),
               "ordering": ("natural", "multicolour", "block_multicolour")}
    for k, allowed in choices.items():
        if so.get(k) not in allowed:
            fail(path, f"solver.{k} is {so.get(k)!r}, expected one of {', '.join(allowed)}")
    if (so["name"] == "sor") != (so["preconditioner"] == "none"):
        fail(path, "solver.preconditioner is 'none' exactly when solver.name is 'sor'")
    for k in ("relaxation_factor", "preconditioner_relaxation_factor", "tolerance"):
        check_number(path, f"solver.{k}", so.get(k))
    for k in ("multigrid_strength", "multigrid_correction"):
        check_number(path, f"solver.{k}", so.get(k))
    for k in ("max_iterations", "threads", "block_rows", "multigrid_coarsest_rows", "multigrid_max_direct_rows"):
        if not isinstance(so.get(k), int) or isinstance(so.get(k), bool) or so[k] < 0:
            fail(path, f"solver.{k} should be a non-negative integer")
    # added within version 1: absent from older reports
    for k, least in (("multigrid_coarse_interval", 1), ("multigrid_first_level_cycles", 0)):
        if k in so and (not isinstance(so[k], int) or isinstance(so[k], bool) or so[k] < least):
            fail(path, f"solver.{k} should be an integer >= {least}")
    for k in ("warm_start", "extrapolate"):
        if not isinstance(so.get(k), bool):
            fail(path, f"solver.{k} should be a boolean")
    steps = r["steps"]
    if not isinstance(steps, list) or not steps:
        fail(path, "steps should be a non-empty list")
    for i, s in enumerate(steps):
        for k in ("step", "angle_deg", "iterations", "converged", "inverted", "min_size_ratio",
                  "max_skewness_moving", "seconds"):
            if k not in s:
                fail(path, f"steps[{i}].{k} missing")
        if s["step"] != i + 1:
            fail(path, f"steps[{i}].step is {s['step']}, expected {i + 1}")
        for k in ("substeps", "rejected_attempts"):
            if not isinstance(s.get(k), int) or isinstance(s.get(k), bool) or s[k] < 0:
                fail(path, f"steps[{i}].{k} should be a non-negative integer")
        # written since the thread count is chosen by measurement; older reports lack it
        if "threads" in s and (not isinstance(s["threads"], int) or isinstance(s["threads"], bool) or s["threads"] < 1):
            fail(path, f"steps[{i}].threads should be a positive integer")
        for k in ("stiffness", "solve", "check"):
            check_number(path, f"steps[{i}].seconds.{k}", s["seconds"].get(k))
    if not isinstance(r["completed"], bool):
        fail(path, "completed should be a boolean")
    fi = r["first_invalid"]
    if r["completed"]:
        if fi is not None:
            fail(path, "a completed run has first_invalid null")
        if len(steps) != mo["steps"]:
            fail(path, f"a completed run has {mo['steps']} steps, the report lists {len(steps)}")
    else:
        if not isinstance(fi, dict) or not {"step", "angle_deg", "elements"} <= fi.keys():
            fail(path, "an incomplete run needs first_invalid with step, angle_deg, elements")
        if not fi["elements"]:
            fail(path, "first_invalid.elements is empty")
        if fi["step"] != steps[-1]["step"] or steps[-1]["inverted"] != len(fi["elements"]):
            fail(path, "first_invalid disagrees with the last step")
    check_number(path, "final_angle_deg", r["final_angle_deg"], nullable=True)
    check_histogram(path, "quality.moving_boundary", r["quality"]["moving_boundary"])
    check_histogram(path, "quality.all", r["quality"]["all"])
    # added within version 1: optional for older reports, in [0, 180] when there
    for part in ("moving_boundary", "all"):
        if "min_angle_deg" in r["quality"][part]:
            a = r["quality"][part]["min_angle_deg"]
            check_number(path, f"quality.{part}.min_angle_deg", a)
            if not 0 <= a <= 180:
                fail(path, f"quality.{part}.min_angle_deg is {a}, outside [0, 180]")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    for p in sys.argv[1:]:
        validate(p)
    print(f"{len(sys.argv) - 1} report(s) valid")
