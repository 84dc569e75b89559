#!/usr/bin/env python3
"""Runs the benchmark of two builds alternately and prints, per case and
thread count, the median per-step times of each and their ratio new / old ("step" is
stiffness + solve + check of one run, then the median).

    /usr/bin/python3 bench/compare_builds.py OLD_BUILD NEW_BUILD [--runs N] [-- BENCH_ARGS...]

OLD_BUILD and NEW_BUILD are build folders holding bench/spring_motion_bench
(for instance a build of an older commit made with `git worktree add`).
Alternating the two and taking medians keeps a shared machine's changing
load out of the ratios as far as possible; `uptime` is printed before and
after. Default bench arguments: --quick --cases naca_coarse,naca_fine.
"""
import statistics
import subprocess
import sys


def parse(text):
    """(case, threads) -> {column: value} from the bench's main table."""
    rows, case, header = {}, None, None
    for line in text.splitlines():
        if line.startswith("case "):
            header = line.split()
            continue
        if header is None:
            continue
        if not line.strip():
            if rows:
                break
            continue
        parts = line.split()
        # a row is '<case name words> nodes thr steps run_s stiff solve check it ...'
        # or, for the next thread count, the same without the case name
        numeric = 0
        while numeric < len(parts) and not parts[numeric].replace(".", "", 1).isdigit():
            numeric += 1
        if numeric > 0:
            case = " ".join(parts[:numeric])
        vals = parts[numeric:]
        if len(vals) < 7 or case is None:
            continue
        rows[(case, int(vals[1]))] = {
            "run s": float(vals[3]),
            "stiff": float(vals[4]),
            "solve": float(vals[5]),
            "check": float(vals[6]),
            "it": float(vals[7]) if len(vals) > 7 else float("nan"),
        }
        r = rows[(case, int(vals[1]))]
        # where a phase's work moved between stiffness and solve (gathering
        # into the solver's order, say), only their sum compares
        r["step"] = r["stiff"] + r["solve"] + r["check"]
    if not rows:
        raise SystemExit("compare_builds.py: found no table in the bench output:\n" + text)
    return rows


def main():
    args = sys.argv[1:]
    bench_args = ["--quick", "--cases", "naca_coarse,naca_fine"]
    if "--" in args:
        i = args.index("--")
        args, bench_args = args[:i], args[i + 1:]
    runs = 3
    if "--runs" in args:
        i = args.index("--runs")
        runs = int(args[i + 1])
        del args[i:i + 2]
    if len(args) != 2:
        raise SystemExit(__doc__)
    builds = {"old": args[0], "new": args[1]}
    print("uptime before:", subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip())
    samples = {"old": [], "new": []}
    for r in range(runs):
        for name in ("old", "new"):
            exe = builds[name] + "/bench/spring_motion_bench"
            out = subprocess.run([exe] + bench_args, capture_output=True, text=True, check=True).stdout
            samples[name].append(parse(out))
            print(f"run {r + 1}/{runs} {name} done", file=sys.stderr)
    print("uptime after: ", subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip())
    print(f"bench arguments: {' '.join(bench_args)}; {runs} alternating runs each; medians; ratio = new / old")
    cols = ["stiff", "solve", "check", "step", "run s"]
    print(f"{'case':<24}{'thr':>4}" + "".join(f"{c + ' old':>12}{c + ' new':>12}{'ratio':>7}" for c in cols))
    worst = 0.0
    for key in samples["old"][0]:
        if not all(key in s for s in samples["new"]):
            continue
        line = f"{key[0]:<24}{key[1]:>4}"
        for c in cols:
            o = statistics.median(s[key][c] for s in samples["old"])
            n = statistics.median(s[key][c] for s in samples["new"])
            ratio = n / o if o > 0 else float("nan")
            worst = max(worst, ratio)
            line += f"{o:>12.3f}{n:>12.3f}{ratio:>7.2f}"
        print(line)
    print(f"largest ratio new / old: {worst:.2f}")


if __name__ == "__main__":
    main()
