#!/usr/bin/python3
"""Figures of the 3D NACA0012 wing case, like the paper's Figs. 8-10, from the
outputs of `naca0012_wing_3d --report-dir DIR`. Usage:
    make_figures_3d.py DIR OUTDIR [--models a,b,... --prefix NAME]
Writes OUTDIR/naca0012_wing_midspan.png (the tetrahedra cut by the mid-span
plane z = 0 near the wing, original and every model at +alpha_m or its last
valid angle, coloured by R), naca0012_wing_tip.png (the same cut at z = 0.97,
near the tip) and naca0012_wing_histograms.png (R of the tetrahedra touching
the wing: original, lineal, grid-scaled, at +alpha_m and -alpha_m). With
--models, the cuts show those models and are written as NAME_midspan.png and
NAME_tip.png, without the histograms (the element models' figures:
`--models ball_vertex_p2,torsional,ball_vertex,grid_scaled+ball_vertex
--prefix naca0012_wing_element_models`)."""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import meshio  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402

MODELS = ["lineal", "lineal_p2", "blom", "zeng_ethier", "zeng_ethier_dihedral", "grid_scaled"]
TITLES = {"original": "original mesh", "lineal": "lineal (p = 1)", "lineal_p2": "lineal (p = 2)",
          "blom": "semi-torsional (Blom)", "zeng_ethier": "Zeng-Ethier (face angles)",
          "zeng_ethier_dihedral": "Zeng-Ethier (dihedral)", "grid_scaled": "grid-scaled (the paper's)",
          "torsional": "torsional (Degand-Farhat)", "ball_vertex": "ball-vertex, k = 1/h",
          "ball_vertex_p2": "ball-vertex, k = 1/h^2", "ball_vertex_p2.5": "ball-vertex, k = 1/h^2.5",
          "ball_vertex_p3": "ball-vertex, k = 1/h^3",
          "grid_scaled+ball_vertex": "grid-scaled + ball-vertex"}
EDGES = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)]


def load(directory, name):
    mesh = meshio.read(os.path.join(directory, name + ".vtu"))
    tet = mesh.cells_dict["tetra"]
    r = np.asarray(mesh.cell_data_dict["skewness"]["tetra"]).reshape(-1)
    return mesh.points, tet, r


def report(directory, name):
    with open(os.path.join(directory, name + ".json")) as f:
        return json.load(f)


def cut(pts, tet, r, z0, window):
    """Polygons where the plane z = z0 cuts the tetrahedra, with their R."""
    z = pts[tet, 2] - z0
    crossing = (z.min(axis=1) < 0) & (z.max(axis=1) > 0)
    xy = pts[tet, :2]
    cx, cy = xy[..., 0].mean(axis=1), xy[..., 1].mean(axis=1)
    pad = 0.3
    inside = (cx > window[0] - pad) & (cx < window[1] + pad) & (cy > window[2] - pad) & (cy < window[3] + pad)
    polys, values = [], []
    for t in np.nonzero(crossing & inside)[0]:
        p = pts[tet[t]]
        zt = z[t]
        q = []
        for a, b in EDGES:
            if (zt[a] < 0) != (zt[b] < 0):
                s = zt[a] / (zt[a] - zt[b])
                q.append(p[a, :2] + s * (p[b, :2] - p[a, :2]))
        q = np.array(q)
        c = q.mean(axis=0)
        q = q[np.argsort(np.arctan2(q[:, 1] - c[1], q[:, 0] - c[0]))]
        polys.append(q)
        values.append(r[t])
    return polys, np.array(values)


def draw(ax, polys, values, window, title):
    pc = PolyCollection(polys, array=values, cmap="viridis_r", edgecolors="k", linewidths=0.15)
    pc.set_clim(0, 1)
    ax.add_collection(pc)
    ax.set_xlim(window[0], window[1])
    ax.set_ylim(window[2], window[3])
    ax.set_aspect("equal")
    ax.set_title(title, fontsize=9)
    ax.tick_params(labelsize=7)
    return pc


def state(rep):
    if rep["completed"]:
        return f"{rep['final_angle_deg']:.0f} deg reached"
    return f"inverts at step {rep['first_invalid']['step']}, last valid {rep['final_angle_deg']:.1f} deg"


def slices(src, out, z0, window, filename, label, models):
    names = ["original"] + [m for m in models if os.path.exists(os.path.join(src, m + "_pos.vtu"))]
    cols = min(4, len(names))
    rows = (len(names) + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(4 * cols, 3.4 * rows), constrained_layout=True, squeeze=False)
    pc = None
    for ax, name in zip(axes.flat, names):
        pts, tet, r = load(src, name if name == "original" else name + "_pos")
        polys, values = cut(pts, tet, r, z0, window)
        title = TITLES[name] if name == "original" else f"{TITLES[name]}\n{state(report(src, name + '_pos'))}"
        pc = draw(ax, polys, values, window, title)
    for ax in list(axes.flat)[len(names):]:
        ax.axis("off")
    fig.colorbar(pc, ax=axes, shrink=0.6, label="equiangle skewness R")
    fig.suptitle(f"NACA0012 wing, tetrahedra cut by the plane {label}, positive pitch about (0.5, 0)")
    fig.savefig(os.path.join(out, filename), dpi=130)
    plt.close(fig)


def histograms(src, out):
    fig, axes = plt.subplots(1, 2, figsize=(11, 3.8), constrained_layout=True)
    bins = np.arange(10) / 10 + 0.05
    for ax, sign in zip(axes, ["pos", "neg"]):
        series = [("original", None)]
        for m in ["lineal", "grid_scaled"]:
            if os.path.exists(os.path.join(src, f"{m}_{sign}.json")):
                series.append((m, report(src, f"{m}_{sign}")))
        width = 0.8 / len(series) / 10
        for k, (name, rep) in enumerate(series):
            if rep is None:
                h = np.array(report(src, "original_quality")["quality"]["moving_boundary"]["histogram"])
                label = "original"
            else:
                h = np.array(rep["quality"]["moving_boundary"]["histogram"])
                label = f"{TITLES[name]} ({state(rep)})"
            ax.bar(bins + (k - (len(series) - 1) / 2) * width, 100 * h, width=width, label=label)
        ax.set_xlabel("equiangle skewness R")
        ax.set_ylabel("% of tetrahedra touching the wing")
        ax.set_title("pitch " + ("+" if sign == "pos" else "-") + "alpha_m", fontsize=10)
        ax.set_xticks(np.arange(11) / 10)
        ax.legend(fontsize=7)
    fig.savefig(os.path.join(out, "naca0012_wing_histograms.png"), dpi=130)
    plt.close(fig)


def main():
    args = sys.argv[1:]
    models, prefix = MODELS, "naca0012_wing"
    if len(args) == 6 and args[2] == "--models" and args[4] == "--prefix":
        models, prefix = args[3].split(","), args[5]
        unknown = [m for m in models if m not in TITLES]
        if unknown:
            sys.exit(f"make_figures_3d.py: unknown model(s) {unknown}; known: {sorted(TITLES)}")
    elif len(args) != 2:
        sys.exit(__doc__)
    src, out = args[0], args[1]
    os.makedirs(out, exist_ok=True)
    slices(src, out, 0.0, (-0.3, 1.4, -0.6, 0.6), prefix + "_midspan.png", "z = 0 (mid-span)", models)
    slices(src, out, 0.97, (-0.3, 1.4, -0.6, 0.6), prefix + "_tip.png", "z = 0.97 (near the tip)", models)
    if models is MODELS:
        histograms(src, out)


if __name__ == "__main__":
    main()
