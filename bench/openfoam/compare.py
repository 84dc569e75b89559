#!/usr/bin/python3
# Copyright (c) 2026 SpringMotion developers.
"""SpringMotion's `spring-motion deform` next to OpenFOAM's moveDynamicMesh.

Run through compare.sh (which installs Debian's openfoam package and sets up
its environment); see README.md beside this file. Both tools move the same
Gmsh mesh by the same quarter-sine pitch alpha_i = alpha_m sin(pi i / (2n)),
counter-clockwise about z:

* 2D: data/naca0012_2d.msh, about (0.25, 0), to 45 degrees. OpenFOAM gets the
  mesh extruded one prism deep (extrude_2d.py) with `empty` front and back.
* 3D: the wing of scripts/make_gmsh_wing.py, about (0.5, 0, 0), to 30 degrees.

OpenFOAM: dynamicMotionSolverFvMesh, displacementLaplacian with inverseDistance
diffusivity from the wing, GAMG for cellDisplacement, the wing patch moved by
angularOscillatingDisplacement (Rodrigues' rotation of the initial points by
alpha_m sin(pi t / 2), t = i/n: the quarter-sine exactly), the far field
fixed; moveDynamicMesh checks the mesh after every step. SpringMotion: its
default model (grid_scaled, or --model) and solver on one thread, like
serial OpenFOAM.

Both final meshes are measured by mesh_quality.py (minimum triangle angle in
2D, minimum dihedral angle in 3D, inverted elements against the initial mesh).
Times are CPU seconds (user + system of the process, so other programs on a
busy machine inflate them less than wall-clock time) per step computed
(SpringMotion stops at the step it refuses, which counts): the whole run
(reading, set-up, writing) divided by the steps, and the steps only, without
the start-up: for OpenFOAM the differences of the ExecutionTime it prints
after every step, for SpringMotion the whole run less a run of its first step
alone, divided by the other steps.
"""
import argparse
import json
import math
import os
import re
import resource
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
import mesh_quality  # noqa: E402

CASES = {
    "2d": {"mesh": "data/naca0012_2d.msh", "wing": "airfoil", "farfield": "farfield",
           "center": (0.25, 0.0, 0.0), "amplitude": 45.0},
    "3d": {"mesh": None, "wing": "wing", "farfield": "farfield",
           "center": (0.5, 0.0, 0.0), "amplitude": 30.0},
}


def run(cmd, log, cwd=None):
    """Runs cmd with output to log; returns (exit status, CPU seconds, wall seconds)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.monotonic()
    with open(log, "w") as out:
        status = subprocess.call(cmd, stdout=out, stderr=subprocess.STDOUT, cwd=cwd)
    wall = time.monotonic() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return status, cpu, wall


def must(cmd, log, cwd=None):
    status, _, _ = run(cmd, log, cwd)
    if status != 0:
        sys.exit("compare.py: %s failed (status %d), see %s" % (cmd[0], status, log))


# ---------------------------------------------------------------- meshes

def prepare_meshes(args, work):
    """Gmsh meshes for both tools and the OpenFOAM polyMesh of each case."""
    meshes = {}
    for name in args.cases:
        case = CASES[name]
        d = os.path.join(work, "mesh_" + name)
        os.makedirs(d, exist_ok=True)
        if name == "2d":
            gmsh_mesh = os.path.join(ROOT, case["mesh"])
            foam_msh = os.path.join(d, "extruded.msh")
            if not os.path.exists(foam_msh):
                must(["/usr/bin/python3", os.path.join(HERE, "extrude_2d.py"), gmsh_mesh, foam_msh],
                     os.path.join(d, "log.extrude"))
        else:
            gmsh_mesh = os.path.join(d, "wing.msh")
            if not os.path.exists(gmsh_mesh):
                print("generating the wing mesh (scripts/make_gmsh_wing.py, about 1-2 min) ...", flush=True)
                must(["/usr/bin/python3", os.path.join(ROOT, "scripts", "make_gmsh_wing.py"),
                      gmsh_mesh + ".tmp.msh"], os.path.join(d, "log.make_gmsh_wing"))
                os.rename(gmsh_mesh + ".tmp.msh", gmsh_mesh)
            foam_msh = gmsh_mesh
        poly = os.path.join(d, "foam")
        if not os.path.exists(os.path.join(poly, "constant", "polyMesh", "owner")):
            shutil.rmtree(poly, ignore_errors=True)
            shutil.copytree(os.path.join(HERE, "case", "system"), os.path.join(poly, "system"))
            control = os.path.join(poly, "system", "controlDict")
            with open(control) as f:
                text = f.read().replace("@DELTA_T@", "1").replace("@WRITE_INTERVAL@", "1")
            with open(control, "w") as f:
                f.write(text)
            must(["gmshToFoam", foam_msh], os.path.join(d, "log.gmshToFoam"), cwd=poly)
            if name == "2d":
                boundary = os.path.join(poly, "constant", "polyMesh", "boundary")
                with open(boundary) as f:
                    text = f.read()
                text, count = re.subn(r"(frontAndBack\s*\{\s*type\s+)patch;(\s*physicalType\s+)patch;",
                                      r"\1empty;\2empty;", text)
                if count != 1:
                    sys.exit("compare.py: no frontAndBack patch in " + boundary)
                with open(boundary, "w") as f:
                    f.write(text)
        meshes[name] = (gmsh_mesh, poly)
    return meshes


# ---------------------------------------------------------------- OpenFOAM

def foam_case(name, poly, steps, amplitude, run_dir):
    case = CASES[name]
    shutil.rmtree(run_dir, ignore_errors=True)
    shutil.copytree(os.path.join(HERE, "case"), run_dir)
    shutil.copytree(os.path.join(poly, "constant", "polyMesh"), os.path.join(run_dir, "constant", "polyMesh"))
    empty = "    frontAndBack { type empty; }" if name == "2d" else ""
    values = {
        "DELTA_T": repr(1.0 / steps), "WRITE_INTERVAL": str(steps),
        "WING": case["wing"], "FARFIELD": case["farfield"],
        "ORIGIN": "(%r %r %r)" % case["center"], "AMPLITUDE_RAD": repr(math.radians(amplitude)),
        "EXTRA_POINT_PATCHES": empty, "EXTRA_CELL_PATCHES": empty,
    }
    for sub in ("system", "constant", "0"):
        for fname in os.listdir(os.path.join(run_dir, sub)):
            path = os.path.join(run_dir, sub, fname)
            if not os.path.isfile(path):
                continue
            with open(path) as f:
                text = f.read()
            for key, value in values.items():
                text = text.replace("@%s@" % key, value)
            with open(path, "w") as f:
                f.write(text)


def parse_foam_log(log, steps):
    """Per step: negative volume / failed checks; the ExecutionTime sequence."""
    with open(log) as f:
        text = f.read()
    first_negative = first_failed = None
    exec_times = []
    for block in re.split(r"^Time = ", text, flags=re.M)[1:]:
        t = float(block.split()[0])
        step = int(round(t * steps))
        if first_negative is None and re.search(r"negative cell volume|Error in face pyramids", block):
            first_negative = step
        if first_failed is None and re.search(r"Failed \d+ mesh check", block):
            first_failed = step
        m = re.search(r"ExecutionTime = ([0-9.eE+-]+) s", block)
        if m:
            exec_times.append(float(m.group(1)))
    return first_negative, first_failed, exec_times


def finished_foam_run(run_dir):
    """CPU and wall seconds of a finished earlier run in run_dir, or None.

    From its log: the last ExecutionTime (CPU seconds of the serial process)
    and ClockTime; they miss only the moments before OpenFOAM starts its clock.
    """
    log = os.path.join(run_dir, "log.moveDynamicMesh")
    if not (os.path.exists(log) and os.path.isdir(os.path.join(run_dir, "1"))):
        return None
    with open(log) as f:
        text = f.read()
    times = re.findall(r"ExecutionTime = ([0-9.eE+-]+) s\s+ClockTime = ([0-9.eE+-]+) s", text)
    if not re.search(r"^End\s*$", text, re.M) or not times:
        return None
    return float(times[-1][0]), float(times[-1][1])


def run_foam(name, poly, steps, amplitude, work, measure=True, reuse=False):
    run_dir = os.path.join(work, "foam_%s_%g_%d" % (name, amplitude, steps))
    earlier = finished_foam_run(run_dir) if reuse else None
    if earlier:
        cpu, wall = earlier
        print("  OpenFOAM: reusing the finished run in %s (--reuse-foam)" % run_dir, flush=True)
    else:
        foam_case(name, poly, steps, amplitude, run_dir)
        status, cpu, wall = run(["moveDynamicMesh"], os.path.join(run_dir, "log.moveDynamicMesh"), cwd=run_dir)
        if status != 0:
            sys.exit("compare.py: moveDynamicMesh failed (status %d), see %s/log.moveDynamicMesh"
                     % (status, run_dir))
    first_negative, first_failed, exec_times = parse_foam_log(os.path.join(run_dir, "log.moveDynamicMesh"), steps)
    result = {"tool": "OpenFOAM", "steps": steps, "amplitude": amplitude, "cpu": cpu, "wall": wall,
              "completed_steps": len(exec_times), "steps_done": len(exec_times), "first_negative": first_negative, "first_failed": first_failed,
              "final_angle": amplitude * math.sin(math.pi * len(exec_times) / (2 * steps)),
              "cpu_step_no_startup": ((exec_times[-1] - exec_times[0]) / (len(exec_times) - 1)
                                      if len(exec_times) > 1 else None)}
    if measure:
        elems, p0 = mesh_quality.foam_elements(run_dir, name == "2d")
        final_time = "1" if os.path.isdir(os.path.join(run_dir, "1")) else None
        if final_time is None:
            sys.exit("compare.py: moveDynamicMesh wrote no time 1 in " + run_dir)
        pts = mesh_quality.foam_points(os.path.join(run_dir, final_time, "polyMesh", "points"))
        result["quality"] = mesh_quality.measure(elems, pts, p0)
        result["initial_quality"] = mesh_quality.measure(elems, p0, p0)
    return result


# ---------------------------------------------------------------- SpringMotion

def run_spring_motion(name, gmsh_mesh, steps, amplitude, work, exe, measure=True, model="grid_scaled"):
    case = CASES[name]
    out = os.path.join(work, "sm_%s_%s_%g_%d" % (name, model.replace("+", "_"), amplitude, steps))
    os.makedirs(out, exist_ok=True)
    center = ",".join("%r" % c for c in (case["center"][:2] if name == "2d" else case["center"]))
    report = os.path.join(out, "report.json")
    cmd = [exe, "deform", gmsh_mesh, "--moving", case["wing"], "--pitch", repr(amplitude),
           "--center", center, "--steps", str(steps), "--threads", "1", "--quiet",
           "--model", model, "--report", report]
    final = os.path.join(out, "final.mesh")
    if measure:
        cmd += ["--output", final]
    status, cpu, wall = run(cmd, os.path.join(out, "log.spring-motion"))
    if status not in (0, 3):
        sys.exit("compare.py: spring-motion failed (status %d), see %s/log.spring-motion" % (status, out))
    with open(report) as f:
        rep = json.load(f)
    first_invalid = rep["first_invalid"]["step"] if rep["first_invalid"] else None
    steps_done = first_invalid or steps  # the refused step was computed too
    result = {"tool": "SpringMotion", "steps": steps, "amplitude": amplitude, "cpu": cpu, "wall": wall,
              "completed": bool(rep["completed"]), "first_negative": first_invalid, "steps_done": steps_done,
              "final_angle": rep["final_angle_deg"], "cpu_step_no_startup": None,
              "model": rep["model"]["name"]}
    if measure and steps_done > 1:
        # The same run's first step alone: reading, set-up and one step. What
        # the full run took more is its other steps_done - 1 steps.
        first = [exe, "deform", gmsh_mesh, "--moving", case["wing"],
                 "--pitch", repr(angle_at(1, steps, amplitude)), "--center", center, "--steps", "1",
                 "--threads", "1", "--quiet", "--model", model]
        status, cpu1, _ = run(first, os.path.join(out, "log.spring-motion-one-step"))
        if status not in (0, 3):
            sys.exit("compare.py: spring-motion failed (status %d), see %s/log.spring-motion-one-step"
                     % (status, out))
        result["cpu_step_no_startup"] = max(0.0, cpu - cpu1) / (steps_done - 1)
    if measure:
        elems, pts, _ = mesh_quality.read_medit(final)
        result["quality"] = mesh_quality.measure(elems, pts, pts)
    return result


# ---------------------------------------------------------------- bisection

def bisect(completes, lo, hi, tol):
    """Largest amplitude in [lo, hi] that completes, to tol; lo must complete."""
    if completes(hi):
        return hi
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        if completes(mid):
            lo = mid
        else:
            hi = mid
    return lo


# ---------------------------------------------------------------- report

def angle_at(step, steps, amplitude):
    return amplitude * math.sin(math.pi * step / (2 * steps))


def print_table(rows):
    print()
    print("| case | tool | n | target | first inverted cell: step (angle) | state measured | min %s (deg) | "
          "inverted cells in it | steps computed | CPU s/step (whole run) | CPU s/step (steps only) | wall s/step |"
          % "angle / dihedral")
    print("|---|---|---:|---:|---|---|---:|---:|---:|---:|---:|---:|")
    for case, r in rows:
        n, amp = r["steps"], r["amplitude"]
        fn = r["first_negative"]
        first = "none" if fn is None else "%d (%.1f deg)" % (fn, angle_at(fn, n, amp))
        if r["tool"] == "OpenFOAM" and r["first_failed"] is not None and r["first_failed"] != fn:
            first += "; first failed checkMesh: step %d" % r["first_failed"]
        q = r.get("quality")
        state = ("final, %.1f deg" % r["final_angle"]) if q else "-"
        if r["tool"] == "SpringMotion" and not r["completed"]:
            state = "last valid, %.1f deg" % r["final_angle"]
        per_step = ("%.4f" % r["cpu_step_no_startup"]) if r["cpu_step_no_startup"] is not None else "-"
        print("| %s | %s | %d | %g deg | %s | %s | %s | %s | %d | %.4f | %s | %.4f |" % (
            case, r["tool"] + (" (%s)" % r["model"] if "model" in r else ""), n, amp, first, state,
            "%.2f" % q["min_angle_deg"] if q else "-", q["inverted"] if q else "-", r["steps_done"],
            r["cpu"] / r["steps_done"], per_step, r["wall"] / r["steps_done"]))
    print()


def main():
    parser = argparse.ArgumentParser(description="SpringMotion next to OpenFOAM's moveDynamicMesh")
    parser.add_argument("--quick", action="store_true", help="10 steps instead of 100")
    parser.add_argument("--steps", type=int, help="steps (overrides --quick)")
    parser.add_argument("--cases", default="2d,3d", help="2d, 3d or 2d,3d (default)")
    parser.add_argument("--steps-3d", type=int, help="steps of the 3D case (default: as --steps)")
    parser.add_argument("--bisect", action="store_true",
                        help="also bisect each tool's largest completing amplitude (slow)")
    parser.add_argument("--bisect-tolerance", type=float, default=0.5, help="degrees")
    parser.add_argument("--reuse-foam", action="store_true",
                        help="take the OpenFOAM runs of the main table from a finished earlier run in --work")
    parser.add_argument("--model", default="grid_scaled",
                        help="SpringMotion's stiffness model (spring-motion deform --model; default grid_scaled)")
    parser.add_argument("--spring-motion", default=os.path.join(ROOT, "build", "src", "cli", "spring-motion"))
    parser.add_argument("--work", default=os.path.join(ROOT, "build", "openfoam_compare"))
    args = parser.parse_args()
    args.cases = [c for c in args.cases.split(",") if c]
    steps = args.steps or (10 if args.quick else 100)
    if not os.access(args.spring_motion, os.X_OK):
        sys.exit("compare.py: no %s: build it first (cmake --build build --target spring-motion)"
                 % args.spring_motion)
    os.makedirs(args.work, exist_ok=True)

    start = time.monotonic()
    meshes = prepare_meshes(args, args.work)
    rows = []
    for name in args.cases:
        gmsh_mesh, poly = meshes[name]
        n = args.steps_3d if (name == "3d" and args.steps_3d) else steps
        amp = CASES[name]["amplitude"]
        print("%s: %s, %d steps to %g deg ..." % (name, os.path.relpath(gmsh_mesh, ROOT), n, amp), flush=True)
        sm = run_spring_motion(name, gmsh_mesh, n, amp, args.work, args.spring_motion, model=args.model)
        of = run_foam(name, poly, n, amp, args.work, reuse=args.reuse_foam)
        rows += [(name, sm), (name, of)]
        print("  initial mesh: min %s %.2f deg" % (of["initial_quality"]["kind"],
                                                   of["initial_quality"]["min_angle_deg"]), flush=True)
        print("  CPU per step: OpenFOAM / SpringMotion = %.1f (whole runs), %.1f (steps only)"
              % ((of["cpu"] / of["steps_done"]) / (sm["cpu"] / sm["steps_done"]),
                 of["cpu_step_no_startup"] / sm["cpu_step_no_startup"]
                 if of["cpu_step_no_startup"] and sm["cpu_step_no_startup"] else float("nan")), flush=True)
    print_table(rows)

    if args.bisect:
        print("largest completing amplitude (bisection to %g deg, %d steps each):" % (args.bisect_tolerance, steps))
        for name in args.cases:
            gmsh_mesh, poly = meshes[name]
            n = args.steps_3d if (name == "3d" and args.steps_3d) else steps

            def sm_ok(a):
                return run_spring_motion(name, gmsh_mesh, n, a, args.work, args.spring_motion,
                                         measure=False, model=args.model)["completed"]

            def of_ok(a):
                return run_foam(name, poly, n, a, args.work, measure=False)["first_negative"] is None

            print("  %s SpringMotion (%s): %.1f deg"
                  % (name, args.model, bisect(sm_ok, 0.0, 90.0, args.bisect_tolerance)),
                  flush=True)
            print("  %s OpenFOAM: %.1f deg (no negative volume at any step)"
                  % (name, bisect(of_ok, 0.0, 90.0, args.bisect_tolerance)), flush=True)
    print("total time of this comparison: %.0f s" % (time.monotonic() - start))


if __name__ == "__main__":
    main()
