#!/usr/bin/python3
# Copyright (c) 2026 SpringMotion developers.
"""Whole-process time of two `spring-motion` builds on the same command,
run in turns (old, new, old, new, ...) so that a shared machine's changing
load falls on both alike.

    bench/alternate_runs.py OLD_CLI NEW_CLI [--rounds 20] -- DEFORM_ARGS...

DEFORM_ARGS follow `spring-motion`, for instance
`deform MESH --moving 1 --pitch 45 --center 0.25,0 --steps 100 --quiet
--output o.vtu`. Prints `uptime` before and after, then each build's median,
minimum and maximum wall time and the ratio of the medians (new / old).
With `--phases` the command must write a JSON report (`--report FILE`):
each run's median per-step stiffness, solve and check seconds are read
from it, and the medians of those over the runs printed for each build.
`--cpu N` runs both builds on CPU N only (`taskset -c N`): the two virtual
CPUs of the benchmark machine were seen to differ by 1.4x in speed for
minutes at a time (docs/performance.md, "Measuring on this machine"), so an
unpinned one-thread run measures partly which CPU it landed on. Besides the
ratio of the medians, the median of the round-by-round ratios is printed:
each pairs two runs a few seconds apart.
A run that fails stops the script with its exit status.
"""
import argparse
import json
import statistics
import subprocess
import sys
import time


def main():
    argv = sys.argv[1:]
    if "--" not in argv:
        sys.exit("usage: alternate_runs.py OLD_CLI NEW_CLI [--rounds N] -- DEFORM_ARGS...")
    split = argv.index("--")
    parser = argparse.ArgumentParser()
    parser.add_argument("old")
    parser.add_argument("new")
    parser.add_argument("--rounds", type=int, default=20)
    parser.add_argument("--phases", action="store_true")
    parser.add_argument("--cpu", type=int, help="run both builds on this CPU only (taskset -c)")
    args = parser.parse_args(argv[:split])
    command = argv[split + 1:]
    report = None
    if args.phases:
        if "--report" not in command or command.index("--report") + 1 >= len(command):
            sys.exit("--phases needs the command to write a report: --report FILE")
        report = command[command.index("--report") + 1]
    phases = ("stiffness", "solve", "check")
    phase_times = {label: {p: [] for p in phases} for label in ("old", "new")}
    print("before:", subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip())
    times = {"old": [], "new": []}
    for _ in range(args.rounds):
        for label in ("old", "new"):
            start = time.perf_counter()
            pin = [] if args.cpu is None else ["taskset", "-c", str(args.cpu)]
            run = subprocess.run(pin + [getattr(args, label)] + command, stdout=subprocess.DEVNULL,
                                 stderr=subprocess.PIPE, text=True)
            elapsed = time.perf_counter() - start
            if run.returncode != 0:
                sys.stderr.write(run.stderr)
                sys.exit(f"{label} build failed with exit status {run.returncode}")
            times[label].append(elapsed)
            if report:
                with open(report) as f:
                    steps = json.load(f)["steps"]
                for p in phases:
                    phase_times[label][p].append(statistics.median(s["seconds"][p] for s in steps))
    print("after: ", subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip())
    for label in ("old", "new"):
        t = times[label]
        print(f"{label}  median {1e3 * statistics.median(t):8.1f} ms  min {1e3 * min(t):8.1f}  "
              f"max {1e3 * max(t):8.1f}  ({len(t)} runs)")
    print(f"new / old (medians): {statistics.median(times['new']) / statistics.median(times['old']):.3f}")
    paired = [n / o for o, n in zip(times["old"], times["new"])]
    print(f"new / old (median of the {len(paired)} rounds' ratios): {statistics.median(paired):.3f}")
    if report:
        print("per step (median over the run's steps, then over the runs), ms:")
        for label in ("old", "new"):
            print(f"{label}  " + "  ".join(f"{p} {1e3 * statistics.median(phase_times[label][p]):8.2f}"
                                           for p in phases))


if __name__ == "__main__":
    main()
