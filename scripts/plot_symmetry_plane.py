#!/usr/bin/python3
# Copyright (c) 2026 SpringMotion developers.
"""The symmetry plane of a half-wing run: a table or a figure.

    plot_symmetry_plane.py --table INITIAL.msh OUT.msh...
        per output: the vertices of the "symmetry" group off the wing, the
        largest |z - z0| of them (0 means bit for bit on the plane) and their
        largest in-plane displacement (how far they slid)
    plot_symmetry_plane.py --check INITIAL.msh OUT.msh
        fails unless every such vertex keeps z bit for bit and some slid
    plot_symmetry_plane.py --figure PNG INITIAL.msh OUT.msh...
        the symmetry plane's triangles near the wing root, one panel per mesh

Meshes are Gmsh 4.1 files with the physical group "symmetry" (written by
scripts/make_gmsh_wing.py --half and by spring-motion deform --output);
read with Debian's python3-meshio.
"""
import argparse
import contextlib
import io
import json
import pathlib
import sys

import numpy as np
import meshio


def group_triangles(m, path, name):
    if name not in m.field_data:
        sys.exit("%s: no physical group '%s'" % (path, name))
    tag = m.field_data[name][0]
    tris = []
    for block, phys in zip(m.cells, m.cell_data["gmsh:physical"]):
        if block.type == "triangle":
            tris.append(block.data[np.asarray(phys) == tag])
    return np.concatenate(tris)


def read(path):
    # meshio's Gmsh reader prints blank lines to stdout
    with contextlib.redirect_stdout(io.StringIO()):
        return meshio.read(path)


def symmetry_triangles(path):
    m = read(path)
    return m.points, group_triangles(m, path, "symmetry")


def sliding_vertices(path):
    """The symmetry plane's vertices that are not on the wing (those move)."""
    m = read(path)
    sym = np.unique(group_triangles(m, path, "symmetry"))
    return np.setdiff1d(sym, np.unique(group_triangles(m, path, "wing")))


def plane_figures(initial, output):
    x0, t0 = symmetry_triangles(initial)
    x, t = symmetry_triangles(output)
    if x.shape != x0.shape or not np.array_equal(t, t0):
        sys.exit("%s: not the same mesh as %s" % (output, initial))
    v = sliding_vertices(initial)
    kept = bool(np.all(x[v, 2] == x0[v, 2]))
    dz = np.abs(x[v, 2] - x0[v, 2]).max()
    slide = np.hypot(x[v, 0] - x0[v, 0], x[v, 1] - x0[v, 1]).max()
    return v.size, kept, dz, slide


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    g = p.add_mutually_exclusive_group(required=True)
    g.add_argument("--table", action="store_true")
    g.add_argument("--check", action="store_true")
    g.add_argument("--figure", metavar="PNG")
    p.add_argument("initial")
    p.add_argument("outputs", nargs="+")
    a = p.parse_args()
    if a.check:
        for path in a.outputs:
            n, kept, dz, slide = plane_figures(a.initial, path)
            if not kept:
                sys.exit("%s: a vertex of the symmetry plane left it (|z - z0| up to %g)" % (path, dz))
            if not slide > 1e-3:
                sys.exit("%s: no vertex of the symmetry plane slid (largest in-plane motion %g)" % (path, slide))
            print("%s: %d plane vertices keep z bit for bit, slid up to %.4f" % (path, n, slide))
        return
    if a.table:
        print("%-28s %9s %14s %12s" % ("output", "vertices", "max |z - z0|", "max slide"))
        for path in a.outputs:
            n, kept, dz, slide = plane_figures(a.initial, path)
            print("%-28s %9d %14.3g %12.4f" % (pathlib.Path(path).name, n, dz, slide))
        return
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    paths = [a.initial] + a.outputs
    fig, axes = plt.subplots(1, len(paths), figsize=(4.2 * len(paths), 3.6), squeeze=False)
    for ax, path in zip(axes[0], paths):
        x, t = symmetry_triangles(path)
        ax.triplot(x[:, 0], x[:, 1], t, lw=0.3, color="k")
        ax.set_xlim(-0.4, 1.4)
        ax.set_ylim(-0.7, 0.7)
        ax.set_aspect("equal")
        title = pathlib.Path(path).stem
        report = pathlib.Path(path).with_suffix(".json")  # the run's report beside its mesh, if any
        if report.exists():
            r = json.loads(report.read_text())
            title += ": %s at %.2f deg" % ("completed" if r["completed"] else "last valid", r["final_angle_deg"])
        ax.set_title(title, fontsize=9)
    fig.tight_layout()
    fig.savefig(a.figure, dpi=130)


if __name__ == "__main__":
    main()
