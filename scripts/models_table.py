#!/usr/bin/python3
"""How far each stiffness model turns a wing (or the 2D airfoil) and how good
the mesh stays: for every model and both directions, the largest pitch
amplitude whose 100-step quarter-sine run completes (found by bisection to
1 degree, up to --up-to), the smallest angle of the elements touching the body
at that amplitude and at 30 degrees, and the time and solver iterations per
step of the run to 30 degrees. Every run goes through `spring-motion deform`.

    /usr/bin/python3 scripts/models_table.py [--build build]
        [--meshes mesh3,gmsh,airfoil,mesh3_first] [--models a,b,...] [--directions +,-]
        [--up-to DEG] [--threads T] [--out FILE [--merge]] [--plan] [--figures DIR]

Meshes: `mesh3` is the wing demo's CGAL Mesh_3 wing (written by
`naca0012_wing_3d --mesh-only`), `gmsh` an independent Gmsh wing of the same
size (scripts/make_gmsh_wing.py, Debian's python3-gmsh), `mesh3_first` the
demo's first default Mesh_3 wing (no ODT, sliver bound 10, no sliver pass),
all pitched about the z axis through (0.5, 0, 0) up to 180 degrees;
`airfoil` the 2D airfoil data/naca0012_2d.msh about (0.25, 0) up to 720
degrees. The runs' JSON
reports are kept under BUILD/models_table/ and reused, so an interrupted
table resumes where it stopped and a model can be added later; the table
(Markdown, written whole or not at all) says which runs it lacks. With
--merge, FILE keeps the sections of the meshes not run this time, and the
lines saying when and at what load its runs were made, for each set of
runs. With
--figures, each wing is also drawn at every model's largest positive
amplitude (mid-span and tip cuts coloured by R, scripts/make_figures_3d.py)
into DIR/<mesh>_wing_largest_angle_{midspan,tip}.png.

A run to a larger amplitude visits the smaller angles on another path, so the
search assumes what every run here showed: a model that completes an
amplitude completes every smaller one. Its next guess after a failing run is
the last angle that run reached, which usually settles the answer in two or
three runs.
"""
import argparse
import glob
import json
import math
import os
import statistics
import subprocess
import sys
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

MODELS_3D = ["lineal", "lineal_p2", "blom", "zeng_ethier", "grid_scaled", "torsional", "ball_vertex",
             "ball_vertex_p2", "ball_vertex_p2.5", "ball_vertex_p3", "grid_scaled+ball_vertex"]
MODELS_2D = ["grid_scaled", "torsional", "ball_vertex", "ball_vertex_p2", "ball_vertex_p2.5", "ball_vertex_p3",
             "grid_scaled+ball_vertex"]

MESHES = {
    "mesh3": dict(title="Mesh_3 wing (the wing demo's default mesh: ODT, sliver bounds 20, sliver pass, the "
                        "tetrahedra in folds of the wing's surface given to the wing)",
                  # the same mesh's section before that last pass, replaced by --merge
                  former_titles=["Mesh_3 wing (the wing demo's default mesh: ODT, sliver bounds 20, sliver pass)"],
                  moving="wing", center="0.5,0,0", up_to=180, models=MODELS_3D, mesh_options=[]),
    "gmsh": dict(title="Gmsh wing (scripts/make_gmsh_wing.py)", moving="wing", center="0.5,0,0", up_to=180,
                 models=MODELS_3D),
    "airfoil": dict(title="2D airfoil (data/naca0012_2d.msh)", moving="airfoil", center="0.25,0", up_to=720,
                    models=MODELS_2D),
    # the demo's first default, kept for comparison: Mesh_3 alone, whose
    # slivers at the tip outline stop the edge models near 20 degrees
    "mesh3_first": dict(title="Mesh_3 wing, the demo's first default (no ODT, sliver bound 10, no sliver pass)",
                        moving="wing", center="0.5,0,0", up_to=180,
                        # its table predates ball_vertex_p3 and ball_vertex_p2.5
                        models=[m for m in MODELS_3D if m not in ("ball_vertex_p3", "ball_vertex_p2.5")],
                        mesh_options=["--odt", "0", "--sliver-bound", "10", "--sliver-smoothing", "0"]),
}
AT = 30  # the amplitude of the quality and timing columns
# the quality a run to the largest amplitude has at its first step past this
# angle (no run of its own: the run to 180 passes 90 degrees at step 57)
PASSING = 90


def mesh_file(name, build, work):
    if name == "airfoil":
        return os.path.join(REPO, "data", "naca0012_2d.msh")
    if name == "gmsh":
        path = os.path.join(work, "gmsh_wing.msh")
        if not os.path.exists(path):
            subprocess.run(["/usr/bin/python3", os.path.join(REPO, "scripts", "make_gmsh_wing.py"), path + ".tmp.msh"],
                           check=True, stdout=subprocess.DEVNULL)
            os.replace(path + ".tmp.msh", path)
        return path
    cache = os.path.join(work, name)
    os.makedirs(cache, exist_ok=True)
    found = glob.glob(os.path.join(cache, "naca0012_wing_*.mesh"))
    if not found:
        subprocess.run([os.path.join(build, "examples", "naca0012_wing_3d"), "--mesh-only", "--mesh-cache", cache,
                        *MESHES[name]["mesh_options"]], check=True, stdout=subprocess.DEVNULL)
        found = glob.glob(os.path.join(cache, "naca0012_wing_*.mesh"))
    if len(found) != 1:
        raise SystemExit(f"models_table.py: expected one wing mesh in {cache}, found {found}")
    return found[0]


class Runner:
    """Runs (or reuses) one pitch run and returns its report."""

    def __init__(self, cli, work, plan_only, threads):
        self.cli, self.work, self.plan_only, self.threads = cli, work, plan_only, threads
        self.missing = 0

    def report(self, mesh_name, mesh, model, amplitude):
        folder = os.path.join(self.work, "runs", mesh_name)
        os.makedirs(folder, exist_ok=True)
        path = os.path.join(folder, f"{model}_{amplitude:+d}.json")
        if os.path.exists(path):
            return json.load(open(path))
        if self.plan_only:
            self.missing += 1
            return None
        print(f"  {mesh_name} {model} {amplitude:+d} deg ...", end="", file=sys.stderr, flush=True)
        start = time.time()
        m = MESHES[mesh_name]
        status = subprocess.run([self.cli, "deform", mesh, "--moving", m["moving"],
                                 "--pitch", str(amplitude), "--center", m["center"], "--steps", "100", "--model", model,
                                 *(["--threads", str(self.threads)] if self.threads else []),
                                 "--quiet", "--report", path], stdout=subprocess.DEVNULL).returncode
        if status not in (0, 3):
            raise SystemExit(f"models_table.py: spring-motion exited with {status} on {mesh_name} {model} {amplitude}")
        r = json.load(open(path))
        with open(os.path.join(self.work, "runs.log"), "a") as log:
            log.write(f"{time.strftime('%Y-%m-%dT%H:%M:%S', time.gmtime(start))}Z load {os.getloadavg()[0]:.2f} "
                      f"{mesh_name} {model} {amplitude:+d} {time.time() - start:.1f} s "
                      f"{'completes' if r['completed'] else 'stops'} threads {r['steps'][0]['threads'] if r['steps'] else '-'}\n")
        print(f" {'completes' if r['completed'] else 'stops at %.1f' % last_valid(r)['angle_deg']}"
              f" ({time.time() - start:.0f} s)", file=sys.stderr)
        return r


def last_valid(report):
    valid = [s for s in report["steps"] if s["inverted"] == 0]
    return valid[-1] if valid else {"angle_deg": 0.0, "min_angle_deg_moving": None}


def largest_amplitude(run, up_to, sign, first):
    """Bisection on whole degrees; `first` is the run to AT degrees. Returns
    (amplitude, its report) or (None, None) when a run it needs is missing."""
    lo, lo_report, hi, guess, stride = 0, None, up_to + 1, None, 1

    def learn(a, r):
        nonlocal lo, lo_report, hi, guess, stride
        if r["completed"]:
            # gallop up from an amplitude that completes: 1, 2, 4, ... degrees further
            lo, lo_report, guess = a, r, a + stride
            stride *= 2
        else:
            hi, stride = a, 1
            guess = int(math.floor(abs(last_valid(r)["angle_deg"])))

    if first is None:
        return None, None
    learn(AT, first)
    if lo == AT:
        r = run(sign * up_to)
        if r is None:
            return None, None
        learn(up_to, r)
    while hi - lo > 1:
        a = guess if guess is not None and lo < guess < hi else (lo + hi) // 2
        r = run(sign * a)
        if r is None:
            return None, None
        learn(a, r)
    return lo, lo_report


def draw_at_largest(name, mesh, runs, cli, work, out):
    """The wing at each model's largest positive amplitude, as VTU files that
    scripts/make_figures_3d.py cuts and colours."""
    folder = os.path.join(work, "figures", name)
    os.makedirs(folder, exist_ok=True)
    jobs = [("original", ["--translate", "0,0,0", "--steps", "1"])]
    jobs += [(model + "_pos", ["--pitch", str(a), "--center", MESHES[name]["center"], "--steps", "100", "--model", model])
             for model, a in runs]
    for base, motion in jobs:
        vtu = os.path.join(folder, base + ".vtu")
        if not os.path.exists(vtu):
            print(f"  figure: {name} {base} {' '.join(motion)}", file=sys.stderr, flush=True)
            subprocess.run([cli, "deform", mesh, "--moving", MESHES[name]["moving"], *motion, "--quiet", "--output", vtu,
                            "--report", os.path.join(folder, base + ".json")], check=True,
                           stdout=subprocess.DEVNULL)
    subprocess.run(["/usr/bin/python3", os.path.join(REPO, "scripts", "make_figures_3d.py"), folder, out,
                    "--models", ",".join(m for m, _ in runs), "--prefix", f"{name}_wing_largest_angle"],
                   check=True)


def fmt(x, spec):
    return "-" if x is None else format(x, spec)


def merged(old, new, titles):
    """The table `old` (lines) with the sections of `new` whose titles are
    keys of `titles` in place of its own (or of those with a title the key
    maps to, a mesh's former title), and both tables' closing lines (when and
    at what load each set of runs was made), the new ones naming their
    meshes."""
    def split(lines):
        head, sections, tail, current = [], {}, [], None
        order = []
        for line in lines:
            if line.startswith("### "):
                current = line[4:]
                order.append(current)
                sections[current] = [line]
            elif current is not None and (line.startswith("|") or line == "" and sections[current][-1].startswith("|")
                                          or len(sections[current]) < 3):
                sections[current].append(line)
            elif current is None:
                head.append(line)
            else:
                tail.append(line)
        return head, order, sections, tail
    head, order, sections, tail = split(old)
    _, new_order, new_sections, new_tail = split(new)
    for title in new_order:
        if title not in titles:
            continue
        if title not in sections:
            former = [t for t in titles[title] if t in sections]
            if former:
                order[order.index(former[0])] = title
            else:
                order.append(title)
        sections[title] = new_sections[title]
    tail = [line for line in tail if line]
    new_tail = [line for line in new_tail if line]
    # an earlier re-make of the same meshes: its closing lines go with it
    prefix = f"Re-made for the {', '.join(titles)}: "
    heads = [line[:len(prefix)] for line in tail]
    if prefix in heads:
        k = heads.index(prefix)
        tail = tail[:k] + tail[k + (2 if k + 1 < len(tail) and tail[k + 1].startswith("Threads:") else 1):]
    out = head + [line for title in order for line in sections[title]]
    return out + tail + ([prefix + new_tail[0]] + new_tail[1:] if new_tail else [])


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build", default=os.path.join(REPO, "build"))
    ap.add_argument("--meshes", default="mesh3,gmsh,airfoil,mesh3_first")
    ap.add_argument("--threads", type=int, help="spring-motion's --threads (default: its own choice)")
    ap.add_argument("--models", help="comma list (default: every model of the mesh's dimension)")
    ap.add_argument("--directions", default="+,-")
    ap.add_argument("--up-to", type=int, help="largest amplitude searched (default 180 for wings, 720 in 2D)")
    ap.add_argument("--out", help="write the table here as well (Markdown)")
    ap.add_argument("--merge", action="store_true",
                    help="replace in --out only the sections of the meshes run now, keeping the others")
    ap.add_argument("--plan", action="store_true", help="run nothing: print the table of the runs kept so far")
    ap.add_argument("--figures", metavar="DIR", help="draw each wing at every model's largest positive amplitude")
    args = ap.parse_args()
    if args.merge and not (args.out and os.path.exists(args.out)):
        raise SystemExit("models_table.py: --merge needs --out naming an existing table")

    build = os.path.abspath(args.build)
    cli = os.path.join(build, "src", "cli", "spring-motion")
    work = os.path.join(build, "models_table")
    os.makedirs(work, exist_ok=True)
    runner = Runner(cli, work, args.plan, args.threads)

    lines = ["# Largest pitch amplitude and mesh quality of every stiffness model", "",
             "Made by `/usr/bin/python3 scripts/models_table.py` (each run: `spring-motion deform`, 100 "
             "quarter-sine steps, default solver). Largest amplitude: the largest whole number of degrees whose "
             "run completes without an inverted element; the angles are the smallest of the elements touching "
             "the body, at the end of that run, at its first step past 90 degrees (where it goes that far) and at the end of "
             "the run to 30 degrees; ms and iterations are medians "
             "over the steps of the run to 30 degrees (to its last valid step where it stops earlier).", ""]
    largest_positive = {}  # mesh -> [(model, amplitude)]
    for name in args.meshes.split(","):
        if name not in MESHES:
            raise SystemExit(f"models_table.py: unknown mesh '{name}' ({', '.join(MESHES)})")
        m = MESHES[name]
        mesh = mesh_file(name, build, work)
        up_to = args.up_to or m["up_to"]
        angle = "dihedral angle" if name != "airfoil" else "angle"
        lines += [f"### {m['title']}", "",
                  f"| model | dir | largest amplitude (deg, to {up_to}) | min {angle} there | "
                  f"min {angle} passing {PASSING} deg | min {angle} at {AT} deg | ms/step at {AT} deg | "
                  "iterations/step |",
                  "|---|---|---|---|---|---|---|---|"]
        for model in (args.models.split(",") if args.models else m["models"]):
            for d in args.directions.split(","):
                sign = 1 if d == "+" else -1
                run = lambda a: runner.report(name, mesh, model, a)
                first = run(sign * AT)
                amplitude, at_max = largest_amplitude(run, up_to, sign, first)
                if first is None:
                    lines.append(f"| {model} | {d} | not run | | | | | |")
                    continue
                steps = [s for s in first["steps"] if s["inverted"] == 0]
                ms = statistics.median(1e3 * sum(s["seconds"].values()) for s in steps) if steps else None
                its = statistics.median(s["iterations"] for s in steps) if steps else None
                at30 = first["quality"]["moving_boundary"]["min_angle_deg"] if first["completed"] else None
                passing = None
                if amplitude is None:
                    largest, there = "search not finished", None
                elif amplitude == 0:
                    largest, there = "< 1", None
                else:
                    largest = f"**{amplitude}**" if amplitude == up_to else str(amplitude)
                    there = at_max["quality"]["moving_boundary"]["min_angle_deg"]
                    past = [s for s in at_max["steps"] if abs(s["angle_deg"]) >= PASSING - 1e-9]
                    passing = past[0]["min_angle_deg_moving"] if past and amplitude > PASSING else None
                    if amplitude == PASSING:
                        passing = there
                    if sign > 0:
                        largest_positive.setdefault(name, []).append((model, amplitude))
                stop = "" if first["completed"] else f" (stops at {last_valid(first)['angle_deg']:.1f})"
                lines.append(f"| {model} | {d} | {largest} | {fmt(there, '.2f')} | {fmt(passing, '.2f')} | "
                             f"{fmt(at30, '.2f')}{stop} | "
                             f"{fmt(ms, '.1f' if ms is not None and ms < 10 else '.0f')} | {fmt(its, '.0f')} |")
        lines.append("")
    log = os.path.join(work, "runs.log")
    if os.path.exists(log):
        runs = [line.split() for line in open(log)]
        lines.append(f"Runs made from {runs[0][0]} to {runs[-1][0]} (UTC); the 1-minute load average as each "
                     f"started was {min(float(r[2]) for r in runs):.2f} to {max(float(r[2]) for r in runs):.2f} "
                     "on 2 cores, so the times compare within a table, not with an idle machine's.")
        threads = [r[r.index("threads") + 1] for r in runs if "threads" in r]
        if threads:
            counts = ", ".join(f"{threads.count(t)} on {t} thread{'' if t == '1' else 's'}" for t in sorted(set(threads)))
            before = (f"{len(runs) - len(threads)} runs before the log recorded them (spring-motion's own choice: 2 "
                      "threads unless it measured one faster), then " if len(runs) > len(threads) else "")
            lines.append(f"Threads: {before}{counts} (as each run's first step took them: `--threads T` where the "
                         "script was given it, else spring-motion's own choice, one thread on small meshes), runs on "
                         "2 threads sharing the 2 cores as the load says.")
    if runner.missing:
        lines.append(f"(At least {runner.missing} {'run is' if runner.missing == 1 else 'runs are'} not made yet: the "
                     "rows they decide say 'not run' or 'search not finished'.)")
    if args.figures:
        for name, runs in largest_positive.items():
            if name != "airfoil":
                draw_at_largest(name, mesh_file(name, build, work), runs, cli, work, args.figures)
    if args.merge:
        lines = merged(open(args.out).read().split("\n"), lines,
                       {MESHES[name]["title"]: MESHES[name].get("former_titles", []) for name in args.meshes.split(",")})
    text = "\n".join(lines) + "\n"
    sys.stdout.write(text)
    if args.out:
        with open(args.out + ".tmp", "w") as f:
            f.write(text)
        os.replace(args.out + ".tmp", args.out)


if __name__ == "__main__":
    main()
