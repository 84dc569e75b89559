#!/usr/bin/env python3
"""Says whether two builds of `spring-motion` move meshes the same way: for
each case and model, the same exit status, the same completed or first
invalid step, and final positions within the solver's tolerance (largest
coordinate difference, the meshes having chord 1).

    /usr/bin/python3 bench/compare_results.py OLD_SPRING_MOTION NEW_SPRING_MOTION [--quick] [--work DIR]

A speed change that moves results by round-off passes; one that changes
which step inverts, or moves vertices by more than the tolerance, fails
(exit status 1). When only the positions differ by more than the
tolerance, both builds run again with a tight solver tolerance (--tight):
round-off differences amplified by the solver's stopping rule shrink with
it and pass, a different motion does not. The meshes are the benchmark's Medit files in
./spring_motion_bench_cache (written by `spring_motion_bench --cases cli`)
and data/naca0012_2d.msh; a missing mesh is skipped and said so.
"""
import argparse
import json
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CACHE = "spring_motion_bench_cache"

# (name, mesh, moving label, pitch args, steps)
CASES = [
    ("2d gmsh", os.path.join(ROOT, "data", "naca0012_2d.msh"), "airfoil", ["--center", "0.25,0"], 45, 100),
    ("2d paper", os.path.join(CACHE, "naca0012_2d_paper.mesh"), "1", ["--center", "0.25,0"], 45, 100),
    ("wing", os.path.join(CACHE, "wing_3d.mesh"), "1", ["--center", "0.25,0,0"], 30, 100),
]
MODELS_2D = ["grid_scaled", "zeng_ethier", "lineal", "grid_scaled+ball_vertex", "torsional", "ball_vertex",
             "ball_vertex_p2", "ball_vertex_p3"]
MODELS_3D = ["grid_scaled", "zeng_ethier", "grid_scaled+ball_vertex", "ball_vertex_p2"]


def read_medit_vertices(path):
    """Vertex coordinates of a Medit ASCII file, as lists of floats."""
    with open(path) as f:
        tokens = f.read().split()
    dim = int(tokens[tokens.index("Dimension") + 1])
    i = tokens.index("Vertices")
    n = int(tokens[i + 1])
    out, k = [], i + 2
    for _ in range(n):
        out.append([float(t) for t in tokens[k:k + dim]])
        k += dim + 1  # the reference
    return out


def run(cli, mesh, moving, extra, amplitude, steps, model, out, solver_tolerance=None):
    if solver_tolerance is not None:
        extra = extra + ["--tolerance", repr(solver_tolerance)]
    args = [cli, "deform", mesh, "--moving", moving, "--pitch", str(amplitude)] + extra + [
        "--steps", str(steps), "--model", model, "--quiet", "--threads", "1",
        "--output", out + ".mesh", "--report", out + ".json"]
    t0 = time.time()
    p = subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    seconds = time.time() - t0
    with open(out + ".json") as f:
        report = json.load(f)
    first = report.get("first_invalid")
    return {
        "status": p.returncode,
        "completed": report["completed"],
        "first_invalid": first["step"] if first else None,
        "points": read_medit_vertices(out + ".mesh"),
        "seconds": seconds,
    }


def max_difference(a, b):
    return max(abs(p - q) for u, v in zip(a["points"], b["points"]) for p, q in zip(u, v))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--quick", action="store_true", help="the 2D cases only")
    ap.add_argument("--work", default="compare_results_work")
    ap.add_argument("--case", help="only this case (2d gmsh, 2d paper or wing)")
    ap.add_argument("--model", help="only these models (comma-separated)")
    ap.add_argument("--direction", choices=["+", "-"], help="only this direction of the pitch")
    ap.add_argument("--tolerance", type=float, default=1e-6,
                    help="largest allowed coordinate difference (default 1e-6, the default solver tolerance)")
    ap.add_argument("--tight", type=float, default=1e-10,
                    help="solver tolerance of the rerun when positions differ by more than --tolerance "
                         "with the same steps (default 1e-10)")
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    print("uptime:", subprocess.run(["uptime"], stdout=subprocess.PIPE, text=True).stdout.strip())
    print(f"{'case':10} {'model':24} {'dir':>4} {'exit old/new':>12} {'first invalid old/new':>22} "
          f"{'max |dx|':>10} {'s old':>7} {'s new':>7}  same?")
    failures = 0
    for name, mesh, moving, extra, amplitude, steps in CASES:
        if a.quick and name == "wing":
            continue
        if not os.path.exists(mesh):
            print(f"{name:10} skipped: {mesh} not found (run spring_motion_bench --cases cli first)")
            continue
        if a.case and name != a.case:
            continue
        models = MODELS_3D if name == "wing" else MODELS_2D
        for model in models:
            if a.model and model not in a.model.split(","):
                continue
            for sign in (+1, -1):
                if a.direction and (a.direction == "+") != (sign > 0):
                    continue
                tag = f"{name.replace(' ', '_')}_{model.replace('+', '_')}_{'p' if sign > 0 else 'm'}"
                r = [run(cli, mesh, moving, extra, sign * amplitude, steps, model, os.path.join(a.work, tag + side))
                     for cli, side in ((a.old, "_old"), (a.new, "_new"))]
                dx = max_difference(r[0], r[1])
                same_steps = (r[0]["status"] == r[1]["status"] and r[0]["first_invalid"] == r[1]["first_invalid"]
                              and len(r[0]["points"]) == len(r[1]["points"]))
                same = same_steps and dx <= a.tolerance
                note = ""
                if same_steps and not same:
                    # Each step stops at the solver's error estimate, so two
                    # builds whose stiffness differs by round-off stop at
                    # different iterates, and on a stiff, ill-conditioned
                    # system 100 such steps can drift apart by more than one
                    # step's tolerance. If the builds compute the same
                    # motion, the drift shrinks with the solver tolerance.
                    tight = [run(cli, mesh, moving, extra, sign * amplitude, steps, model,
                                 os.path.join(a.work, tag + side + "_tight"), a.tight)
                             for cli, side in ((a.old, "_old"), (a.new, "_new"))]
                    dx_tight = max_difference(tight[0], tight[1])
                    same = (tight[0]["first_invalid"] == tight[1]["first_invalid"]
                            and tight[0]["status"] == tight[1]["status"] and dx_tight <= a.tolerance)
                    note = f"  (solver tolerance {a.tight:g}: max |dx| {dx_tight:.2e})"
                failures += not same
                fi = f"{r[0]['first_invalid']}/{r[1]['first_invalid']}"
                print(f"{name:10} {model:24} {'+' if sign > 0 else '-':>4} "
                      f"{str(r[0]['status']) + '/' + str(r[1]['status']):>12} {fi:>22} {dx:10.2e} "
                      f"{r[0]['seconds']:7.2f} {r[1]['seconds']:7.2f}  {'yes' if same else 'NO'}{note}", flush=True)
    print("all the same" if failures == 0 else f"{failures} run(s) differ")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
