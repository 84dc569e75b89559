#!/usr/bin/env python3
"""Says whether regenerated JSON reports reproduce committed ones: every
value equal except timings (any key under "seconds", "seconds_total"), the
thread counts chosen by measuring them ("threads") and fields one side lacks
(listed, not counted as differences). Each differing numeric field is
followed by the largest absolute difference found in it.

    /usr/bin/python3 scripts/compare_reports.py REVISION FILE...

compares each FILE in the work tree with its version at REVISION (for
instance `HEAD` after re-running scripts/naca0012_3d_results.sh). Exit
status 1 when some value differs.
"""
import collections
import json
import subprocess
import sys

TIMING_KEYS = {"seconds", "seconds_total", "threads"}


def walk(old, new, path, differ, missing, largest):
    if isinstance(old, dict) and isinstance(new, dict):
        for k in sorted(set(old) | set(new)):
            if k in TIMING_KEYS:
                continue
            if k not in old or k not in new:
                missing[path + "/" + k + (" (new)" if k in new else " (gone)")] += 1
                continue
            walk(old[k], new[k], path + "/" + k, differ, missing, largest)
    elif isinstance(old, list) and isinstance(new, list):
        if len(old) != len(new):
            differ[path + " (length)"] += 1
            return
        for a, b in zip(old, new):
            walk(a, b, path + "[]", differ, missing, largest)
    elif old != new:
        differ[path] += 1
        numbers = (int, float)
        if isinstance(old, numbers) and isinstance(new, numbers) and not isinstance(old, bool):
            largest[path] = max(largest.get(path, 0.0), abs(new - old))


def main():
    if len(sys.argv) < 3:
        raise SystemExit(__doc__)
    rev, files = sys.argv[1], sys.argv[2:]
    bad = 0
    for f in files:
        shown = subprocess.run(["git", "show", f"{rev}:{f}"], capture_output=True, text=True)
        if shown.returncode != 0:
            print(f"{f}: not in {rev}")
            continue
        old, new = json.loads(shown.stdout), json.load(open(f))
        differ, missing = collections.Counter(), collections.Counter()
        largest = {}
        walk(old, new, "", differ, missing, largest)

        def item(k, n):
            return f"{k} x{n}" + (f" (max |diff| {largest[k]:.2g})" if k in largest else "")

        status = "same values" if not differ else "DIFFERENT: " + ", ".join(item(k, n) for k, n in differ.items())
        extra = ("; fields on one side only: " + ", ".join(sorted(missing))) if missing else ""
        print(f"{f}: {status}{extra}")
        bad += bool(differ)
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
