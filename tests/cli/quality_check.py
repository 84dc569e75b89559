#!/usr/bin/env python3
"""Per-step quality is measured when something shows it, the final state's always.

usage: quality_check.py PROGRAM ARGS...

Runs `PROGRAM ARGS --quiet` twice, once with `--report q.json`: the summary
lines must agree up to the run time (the final quality is measured either
way, and measuring the steps moves nothing), and every step of the report
must carry its quality (R and the smallest angle, near the moving boundary
and overall), which the command computes because a report was asked for.
"""
import json
import math
import re
import subprocess
import sys


def summary(command):
    done = subprocess.run(command, capture_output=True, text=True, check=True)
    line = done.stdout.strip().splitlines()[-1]
    # the run time and the list of written files differ
    return re.sub(r", [0-9.]+ s(;.*)?$", "", line)


def main():
    command = sys.argv[1:] + ["--quiet"]
    plain = summary(command)
    reported = summary(command + ["--report", "q.json"])
    if plain != reported:
        sys.exit(f"summary lines differ:\n  {plain}\n  {reported}")
    with open("q.json") as f:
        report = json.load(f)
    steps = report["steps"]
    if not steps:
        sys.exit("the report has no steps")
    fields = ("max_skewness_moving", "max_skewness_all", "min_angle_deg_moving", "min_angle_deg_all")
    for s in steps:
        for k in fields:
            v = s.get(k)
            if not isinstance(v, (int, float)) or not math.isfinite(v):
                sys.exit(f"step {s.get('step')}: {k} is {v!r}, expected a number")
    if report["options"]["quality_every_step"] is not True:
        sys.exit("the report says its steps' quality was not computed")
    print(f"{len(steps)} steps with quality; summary: {plain}")


if __name__ == "__main__":
    main()
