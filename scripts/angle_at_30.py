#!/usr/bin/env python3
"""Prints, for each JSON report of a pitch run, the smallest angle of the
elements touching the moving boundary (steps[].min_angle_deg_moving) at the
first step whose angle reaches 30 degrees in size, and at the last valid step.

    /usr/bin/python3 scripts/angle_at_30.py REPORT.json...
"""
import json
import os
import sys


def main():
    if len(sys.argv) < 2:
        raise SystemExit(__doc__)
    print(f"{'report':<34} {'model':<16} {'step':>5} {'angle':>8} {'min_angle':>10}   "
          f"{'last valid':>10} {'min_angle':>10}")
    for path in sys.argv[1:]:
        r = json.load(open(path))
        steps = [s for s in r["steps"] if s["inverted"] == 0]
        at30 = next((s for s in steps if s["angle_deg"] is not None and abs(s["angle_deg"]) >= 30), None)
        last = steps[-1] if steps else None
        def fmt(s):
            if s is None or s.get("min_angle_deg_moving") is None:
                return f"{'-':>5} {'-':>8} {'-':>10}"
            return f"{s['step']:>5} {s['angle_deg']:>8.2f} {s['min_angle_deg_moving']:>10.2f}"
        tail = f"{last['angle_deg']:>10.2f} {last['min_angle_deg_moving']:>10.2f}" if last else ""
        model = r["model"]["name"]
        p = r["model"]["parameters"].get("exponent")
        if model == "ball_vertex" and p is not None and p != 1:
            model += f" p={p:g}"
        print(f"{os.path.basename(path):<34} {model:<16} {fmt(at30)}   {tail}")


if __name__ == "__main__":
    main()
