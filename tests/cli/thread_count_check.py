#!/usr/bin/env python3
"""`--threads 1` keeps the whole process on one thread.

usage: thread_count_check.py PROGRAM deform ARGS...

Writes grid.mesh, a unit square of 2 x 120^2 triangles (its bottom side
labelled 1, the others 2): large enough that every parallel loop of the run,
the set-up's checks and the output's too, may take two threads. Then runs
`PROGRAM deform grid.mesh ARGS --threads 1` and the same with `--threads 2`, counting the
process's threads (/proc/PID/task) as often as it can while each runs. OpenMP
keeps a team's threads until the process exits, so a region that ran on two
threads anywhere in the run (the set-up's checks, a step, the output) shows
for the rest of it. The two-thread run must show exactly one thread more than
the one-thread run: the count sees the team, and the one-thread run has none
(a sanitizer's own threads, if any, are in both).
"""
import os
import subprocess
import sys


def most_threads(command):
    p = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    most, samples = 0, 0
    while p.poll() is None:
        try:
            most = max(most, len(os.listdir(f"/proc/{p.pid}/task")))
            samples += 1
        except FileNotFoundError:  # it has just ended
            pass
    err = p.stderr.read()
    if p.returncode != 0:
        sys.exit(f"{' '.join(command)}: exit status {p.returncode}\n{err}")
    if samples < 20:
        sys.exit(f"{' '.join(command)}: ended after {samples} samples of its threads; make the run longer")
    return most, samples


def write_grid(path, n=120):
    def v(i, j):
        return j * (n + 1) + i + 1
    lines = ["MeshVersionFormatted 2", "Dimension 2", "Vertices", str((n + 1) ** 2)]
    lines += [f"{i / n} {j / n} 0" for j in range(n + 1) for i in range(n + 1)]
    edges = [(v(i, 0), v(i + 1, 0), 1) for i in range(n)]
    edges += [(v(n, j), v(n, j + 1), 2) for j in range(n)]
    edges += [(v(i + 1, n), v(i, n), 2) for i in range(n)]
    edges += [(v(0, j + 1), v(0, j), 2) for j in range(n)]
    lines += ["Edges", str(len(edges))] + [f"{a} {b} {r}" for a, b, r in edges]
    triangles = []
    for j in range(n):
        for i in range(n):
            triangles += [(v(i, j), v(i + 1, j), v(i + 1, j + 1)), (v(i, j), v(i + 1, j + 1), v(i, j + 1))]
    lines += ["Triangles", str(len(triangles))] + [f"{a} {b} {c} 10" for a, b, c in triangles]
    with open(path, "w") as f:
        f.write("\n".join(lines + ["End", ""]))


def main():
    write_grid("grid.mesh")
    command = sys.argv[1:3] + ["grid.mesh"] + sys.argv[3:]
    one, s1 = most_threads(command + ["--threads", "1"])
    two, s2 = most_threads(command + ["--threads", "2"])
    print(f"--threads 1: at most {one} threads ({s1} samples); --threads 2: at most {two} ({s2} samples)")
    if two != one + 1:
        sys.exit("expected the two-thread run to show exactly one thread more than the one-thread run")


if __name__ == "__main__":
    main()
