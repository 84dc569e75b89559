#!/usr/bin/env python3
"""Runs two builds of `spring-motion` at the same time, each on its own core
(taskset), and prints per round the median per-step stiffness, solve and
check times of each (from --report) and the ratio new / old of each part.

    /usr/bin/python3 bench/paired_runs.py OLD_SPRING_MOTION NEW_SPRING_MOTION [--rounds N] -- DEFORM_ARGS...

DEFORM_ARGS are those of `spring-motion deform` after the command (mesh,
boundary, motion, --steps, --model); --threads 1, --quiet and --report are
added. On a shared virtual machine whose speed changes within minutes, runs
made one after the other compare different machines; two runs at the same
time meet the same one. They share the memory bus, so each is slower than
alone, equally. The cores are swapped every round; the last line gives the
medians of the ratios over the rounds.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

PARTS = ["stiffness", "solve", "check"]


def medians(report_path):
    with open(report_path) as f:
        steps = json.load(f)["steps"]
    return {p: statistics.median(s["seconds"][p] for s in steps) for p in PARTS}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("old")
    parser.add_argument("new")
    parser.add_argument("--rounds", type=int, default=4)
    argv = sys.argv[1:]
    if "--" not in argv or argv.index("--") == len(argv) - 1:
        parser.error("expected -- and the arguments of spring-motion deform")
    a = parser.parse_args(argv[:argv.index("--")])
    deform = argv[argv.index("--") + 1:]
    print("uptime:", subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip())
    ratios = {p: [] for p in PARTS}
    with tempfile.TemporaryDirectory() as work:
        for r in range(a.rounds):
            cores = (0, 1) if r % 2 == 0 else (1, 0)
            runs, reports = [], []
            for build, core in zip((a.old, a.new), cores):
                report = os.path.join(work, "%d_%d.json" % (r, core))
                reports.append(report)
                cmd = ["taskset", "-c", str(core), build, "deform"] + deform + [
                    "--threads", "1", "--quiet", "--report", report]
                runs.append(subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True))
            for run in runs:
                _, err = run.communicate()
                if run.returncode not in (0, 3):  # 3: the run stopped at an inverted element
                    sys.exit("%s failed (exit %d): %s" % (run.args[3], run.returncode, err.strip()))
            old, new = medians(reports[0]), medians(reports[1])
            line = "round %d (old on core %d):" % (r + 1, cores[0])
            for p in PARTS:
                ratios[p].append(new[p] / old[p])
                line += "  %s %.3f / %.3f ms (%.3f)" % (p, 1e3 * old[p], 1e3 * new[p], ratios[p][-1])
            print(line, flush=True)
    print("median new / old over %d rounds: " % a.rounds
          + ", ".join("%s %.3f" % (p, statistics.median(ratios[p])) for p in PARTS))


if __name__ == "__main__":
    main()
