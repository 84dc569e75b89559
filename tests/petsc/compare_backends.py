#!/usr/bin/python3
"""Runs one `spring-motion deform` with the shared backend and with
`--backend petsc` on N MPI ranks, and checks that they agree: the same exit
status, the same completed steps or first invalid step, and final positions
within TOL (Medit outputs, read here).

    compare_backends.py SPRING_MOTION MPIEXEC RANKS TOL -- DEFORM_ARGUMENTS...
"""
import json
import os
import subprocess
import sys
import tempfile


def medit_points(path):
    lines = open(path).read().split("\n")
    i = next(k for k, l in enumerate(lines) if l.split()[:1] == ["Vertices"])
    n = int(lines[i + 1])
    return [[float(x) for x in l.split()[:-1]] for l in lines[i + 2:i + 2 + n]]


def close(a, b, what):
    """Quality figures of positions that agree to the solver's tolerance agree to 1e-4."""
    if a is None or b is None or a != a or b != b:  # not computed (a rejected step): on both sides
        if (a is None or a != a) != (b is None or b != b):
            sys.exit("%s: %r vs %r" % (what, a, b))
        return
    if abs(a - b) > 1e-4 * max(1.0, abs(a)):
        sys.exit("%s: %r vs %r" % (what, a, b))


def main():
    cli, mpiexec, ranks, tol = sys.argv[1], sys.argv[2], int(sys.argv[3]), float(sys.argv[4])
    args = sys.argv[sys.argv.index("--") + 1:]
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    with tempfile.TemporaryDirectory() as tmp:
        runs = {}
        for name, prefix, extra in (("shared", [], []),
                                    ("petsc", [mpiexec, "-n", str(ranks), "--oversubscribe"], ["--backend", "petsc"])):
            out, rep = os.path.join(tmp, name + ".mesh"), os.path.join(tmp, name + ".json")
            c = subprocess.run(prefix + [cli, "deform"] + args + extra + ["--output", out, "--report", rep],
                               capture_output=True, text=True, env=env, timeout=600)
            print("%s: exit %d\n%s%s" % (name, c.returncode, c.stdout, c.stderr))
            runs[name] = (c.returncode, c.stdout, json.load(open(rep)), medit_points(out))
        (e0, o0, r0, p0), (e1, o1, r1, p1) = runs["shared"], runs["petsc"]
        if e0 != e1:
            sys.exit("exit status %d (shared) vs %d (petsc)" % (e0, e1))
        if o1.count("\n") != 1:
            sys.exit("expected one summary line from rank 0 only, got:\n" + o1)
        b = r1["backend"]
        if b["name"] != "petsc" or b["ranks"] != ranks or len(b["seconds_solve_per_rank"]) != ranks \
                or len(b["seconds_total_per_rank"]) != ranks or len(b["peak_mib_per_rank"]) != ranks \
                or not all(m > 0 for m in b["peak_mib_per_rank"]) \
                or not all(0 <= t <= u for t, u in zip(b["seconds_solve_per_rank"], b["seconds_total_per_rank"])):
            sys.exit("report backend %r" % b)
        for k in ("completed",):
            if r0[k] != r1[k]:
                sys.exit("%s: %r vs %r" % (k, r0[k], r1[k]))
        s0 = (r0["first_invalid"] or {}).get("step")
        s1 = (r1["first_invalid"] or {}).get("step")
        if s0 != s1 or len(r0["steps"]) != len(r1["steps"]):
            sys.exit("first invalid step %r vs %r, steps %d vs %d" % (s0, s1, len(r0["steps"]), len(r1["steps"])))
        # the partitioned run's report is reduced over the ranks: it must
        # describe the whole mesh as the shared one does
        if r0["mesh"] != r1["mesh"]:
            sys.exit("mesh %r vs %r" % (r0["mesh"], r1["mesh"]))
        if r0["first_invalid"] and r0["first_invalid"]["elements"] != r1["first_invalid"]["elements"]:
            sys.exit("inverted elements %r vs %r" % (r0["first_invalid"]["elements"], r1["first_invalid"]["elements"]))
        # PETSc's CG stops by the shared solver's rule: the error estimate of
        # every solve within half the tolerance
        tolerance = r1["solver"]["tolerance"]
        for q in r1["steps"]:
            if q["converged"] and q["iterations"] > 0 and not q["error_estimate"] <= 0.5 * tolerance:
                sys.exit("step %d: error estimate %r above half the tolerance %g"
                         % (q["step"], q["error_estimate"], tolerance))
        for q0, q1 in zip(r0["steps"], r1["steps"]):
            if q0["inverted"] != q1["inverted"]:
                sys.exit("step %d: %d vs %d inverted" % (q0["step"], q0["inverted"], q1["inverted"]))
            for k in ("min_size_ratio", "max_size_ratio", "max_skewness_moving", "max_skewness_all",
                      "min_angle_deg_moving", "min_angle_deg_all"):
                close(q0.get(k), q1.get(k), "step %d %s" % (q0["step"], k))
        for k in ("min_size_ratio", "max_size_ratio"):
            close(r0[k], r1[k], k)
        for part in ("moving_boundary", "all"):
            a, b = r0["quality"][part], r1["quality"][part]
            if a["count"] != b["count"] or a["histogram"] != b["histogram"]:
                sys.exit("quality %s: %r vs %r" % (part, a, b))
            for k in ("mean", "max", "min_angle_deg"):
                close(a[k], b[k], "quality %s %s" % (part, k))
        worst = max(abs(a - b) for p, q in zip(p0, p1) for a, b in zip(p, q))
        print("largest position difference %.3g (tolerance %g)" % (worst, tol))
        if not worst <= tol:
            sys.exit("positions differ by %g > %g" % (worst, tol))


if __name__ == "__main__":
    main()
