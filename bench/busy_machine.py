#!/usr/bin/python3
# Copyright (c) 2026 SpringMotion developers.
"""Mesh motion on a shared machine: the default thread choice against one
thread and OpenMP's full team, with the cores idle and with CPU-bound
processes beside the run (a flow solver's ranks, the normal case in FSI).

    bench/busy_machine.py BUILD_DIR [--mesh MESH --moving LABEL] [--steps 20]
                          [--pitch 10] [--repeats 3] [--hogs 2]

Runs `spring-motion deform` (whole process, wall clock) with --threads 1,
--threads N (N = the machine's cores) and without --threads (the default:
team or one thread, chosen step by step by measurement), in turns so that
a changing load falls on all three, first with nothing else started, then
with --hogs busy-looping processes at this script's own priority (run it
without `nice -n -10`, or the runs would simply preempt the hogs). Prints the medians, the ratios to one
thread, and how many steps the default ran on the team (from the reports).
The default mesh is the Gmsh wing of scripts/make_gmsh_wing.py, made into
BUILD_DIR/gmsh_wing/wing.msh when missing.
"""
import argparse
import json
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time


def run(cli, mesh, moving, steps, pitch, threads, report):
    cmd = [cli, "deform", mesh, "--moving", moving, "--pitch", str(pitch), "--center", "0.5,0,0",
           "--axis", "0,0,1", "--steps", str(steps), "--quiet", "--report", report]
    if threads:
        cmd += ["--threads", str(threads)]
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    seconds = time.perf_counter() - t0
    with open(report) as f:
        r = json.load(f)
    team = sum(1 for s in r["steps"] if s.get("threads", 1) > 1)
    return seconds, team, len(r["steps"])


def main():
    here = pathlib.Path(__file__).resolve().parent.parent
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("build")
    p.add_argument("--mesh")
    p.add_argument("--moving", default="wing")
    p.add_argument("--steps", type=int, default=20)
    p.add_argument("--pitch", type=float, default=10)
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--hogs", type=int, default=2)
    a = p.parse_args()
    build = pathlib.Path(a.build)
    cli = str(build / "src" / "cli" / "spring-motion")
    mesh = a.mesh
    if not mesh:
        mesh = str(build / "gmsh_wing" / "wing.msh")
        if not os.path.exists(mesh):
            os.makedirs(os.path.dirname(mesh), exist_ok=True)
            subprocess.run(["/usr/bin/python3", str(here / "scripts" / "make_gmsh_wing.py"), mesh], check=True)
    cores = os.cpu_count()
    configs = [("one thread", 1), ("team (%d threads)" % cores, cores), ("default (chosen)", 0)]
    print("uptime before:", subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip())
    print("mesh %s, %d steps to %g degrees, %d repeats per configuration, medians\n"
          % (mesh, a.steps, a.pitch, a.repeats))
    print("%-10s %-22s %10s %14s %18s" % ("machine", "threads", "median s", "/ one thread", "default: team steps"))
    with tempfile.TemporaryDirectory() as tmp:
        report = os.path.join(tmp, "r.json")
        for state in ("idle", "busy"):
            hogs = []
            if state == "busy":
                # the hogs inherit this process's niceness, like the runs
                hogs = [subprocess.Popen([sys.executable, "-c", "while True: pass"]) for _ in range(a.hogs)]
                time.sleep(1)
            try:
                times = {c: [] for c, _ in configs}
                team = {}
                for _ in range(a.repeats):
                    for name, threads in configs:
                        s, t, n = run(cli, mesh, a.moving, a.steps, a.pitch, threads, report)
                        times[name].append(s)
                        if threads == 0:
                            team[name] = "%d of %d" % (t, n)
                        print("  %s %-20s %7.3f s" % (state, name, s), file=sys.stderr)
            finally:
                for h in hogs:
                    h.kill()
            one = statistics.median(times["one thread"])
            label = state if state == "idle" else "busy (%d)" % a.hogs
            for name, _ in configs:
                m = statistics.median(times[name])
                print("%-10s %-22s %10.3f %14.2f %18s" % (label, name, m, m / one, team.get(name, "")))
    print("\nuptime after:", subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip())


if __name__ == "__main__":
    main()
