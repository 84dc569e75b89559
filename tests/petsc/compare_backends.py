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
                or len(b["seconds_total_per_rank"]) != ranks \
                or not all(0 <= t <= u for t, u in zip(b["seconds_solve_per_rank"], b["seconds_total_per_rank"])):
            sys.exit("report backend %r" % b)
        for k in ("completed",):
            if r0[k] != r1[k]:
                sys.exit("%s: %r vs %r" % (k, r0[k], r1[k]))
        s0 = (r0["first_invalid"] or {}).get("step")
        s1 = (r1["first_invalid"] or {}).get("step")
        if s0 != s1 or len(r0["steps"]) != len(r1["steps"]):
            sys.exit("first invalid step %r vs %r, steps %d vs %d" % (s0, s1, len(r0["steps"]), len(r1["steps"])))
        worst = max(abs(a - b) for p, q in zip(p0, p1) for a, b in zip(p, q))
        print("largest position difference %.3g (tolerance %g)" % (worst, tol))
        if not worst <= tol:
            sys.exit("positions differ by %g > %g" % (worst, tol))


if __name__ == "__main__":
    main()
