#!/usr/bin/python3
"""Figures of the 2D NACA0012 case, like the paper's Figs. 4-6, from the
outputs of `naca0012_pitch_2d --report-dir DIR`. Usage:
    make_figures_2d.py DIR OUTDIR
Writes OUTDIR/naca0012_closeup.png (Fig. 4: the mesh near the airfoil at the
last valid angle, one panel per model), naca0012_histograms.png (Fig. 5: R
near the airfoil: original, torsional, grid-scaled) and naca0012_domain.png
(Fig. 6: the whole domain, grid-scaled at +45 degrees)."""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import meshio  # noqa: E402
import numpy as np  # noqa: E402

MODELS = ["lineal", "lineal_p2", "blom", "zeng_ethier", "grid_scaled", "torsional"]
TITLES = {"lineal": "lineal (p = 1)", "lineal_p2": "lineal (p = 2)", "blom": "semi-torsional (Blom)",
          "zeng_ethier": "semi-torsional (Zeng-Ethier)", "grid_scaled": "grid-scaled (the paper's)",
          "torsional": "torsional (Farhat)"}


def load(directory, name):
    mesh = meshio.read(os.path.join(directory, name + ".vtu"))
    tri = mesh.cells_dict["triangle"]
    r = np.asarray(mesh.cell_data_dict["skewness"]["triangle"]).reshape(-1)
    return mesh.points[:, :2], tri, r


def report(directory, name):
    with open(os.path.join(directory, name + ".json")) as f:
        return json.load(f)


def draw(ax, pts, tri, r, window, title):
    ax.tripcolor(pts[:, 0], pts[:, 1], tri, facecolors=r, cmap="viridis_r", vmin=0, vmax=1,
                 edgecolors="k", linewidth=0.15)
    ax.set_xlim(window[0], window[1])
    ax.set_ylim(window[2], window[3])
    ax.set_aspect("equal")
    ax.set_title(title, fontsize=9)
    ax.tick_params(labelsize=7)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    src, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    window = (-0.35, 1.35, -0.75, 0.75)

    # Fig. 4: close-up of every model at +alpha_m (or its last valid angle)
    fig, axes = plt.subplots(2, 3, figsize=(12, 7.2), constrained_layout=True)
    for ax, model in zip(axes.flat, MODELS):
        pts, tri, r = load(src, model + "_pos")
        rep = report(src, model + "_pos")
        state = "reached" if rep["completed"] else f"inverts at step {rep['first_invalid']['step']}, last valid"
        draw(ax, pts, tri, r, window, f"{TITLES[model]}\n{state} {rep['final_angle_deg']:.1f} deg")
    sm = plt.cm.ScalarMappable(cmap="viridis_r", norm=plt.Normalize(0, 1))
    fig.colorbar(sm, ax=axes, shrink=0.6, label="equiangle skewness R")
    fig.suptitle("NACA0012 pitching about the quarter chord: mesh near the airfoil at the end of the run")
    fig.savefig(os.path.join(out, "naca0012_closeup.png"), dpi=110)
    plt.close(fig)

    # Fig. 5: R histograms of the triangles touching the airfoil
    pts0, tri0, r0 = load(src, "original")
    rep_g = report(src, "grid_scaled_pos")
    fig, axes = plt.subplots(1, 3, figsize=(12, 3.6), sharey=True, constrained_layout=True)
    # the original mesh's histogram over the triangles with a vertex on the
    # airfoil (the boundary away from the far-field circle), checked against
    # the count the library reports for the same set
    airfoil_pts = np.abs(np.hypot(pts0[:, 0] - 0.5, pts0[:, 1]) - 15) > 1e-6
    boundary = np.zeros(len(pts0), dtype=bool)
    edges = {}
    for t in tri0:
        for a, b in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])):
            key = (min(a, b), max(a, b))
            edges[key] = edges.get(key, 0) + 1
    for (a, b), n in edges.items():
        if n == 1:
            boundary[a] = boundary[b] = True
    moving = boundary & airfoil_pts
    touch = moving[tri0].any(axis=1)
    if touch.sum() != rep_g["quality"]["moving_boundary"]["count"]:
        sys.exit("the triangles touching the airfoil disagree with the report's count")
    bins = np.linspace(0, 1, 11)
    h0 = np.histogram(np.minimum(r0[touch], 1 - 1e-12), bins)[0] / touch.sum()
    panels = [("original mesh", h0),
              (f"torsional at {report(src, 'torsional_pos')['final_angle_deg']:.0f} deg",
               report(src, "torsional_pos")["quality"]["moving_boundary"]["histogram"]),
              (f"grid-scaled at {rep_g['final_angle_deg']:.0f} deg", rep_g["quality"]["moving_boundary"]["histogram"])]
    labels = [f"{b:.1f}-{b + 0.1:.1f}" for b in bins[:-1]]
    for ax, (title, h) in zip(axes, panels):
        ax.bar(range(10), 100 * np.asarray(h), color="tab:blue")
        ax.set_xticks(range(10))
        ax.set_xticklabels(labels, rotation=60, fontsize=7)
        ax.set_title(title, fontsize=10)
        ax.set_xlabel("R")
    axes[0].set_ylabel("% of triangles touching the airfoil")
    fig.savefig(os.path.join(out, "naca0012_histograms.png"), dpi=110)
    plt.close(fig)

    # Fig. 6: the whole domain and a wider close-up, grid-scaled at +alpha_m
    pts, tri, r = load(src, "grid_scaled_pos")
    fig, axes = plt.subplots(1, 2, figsize=(12, 5.6), constrained_layout=True)
    draw(axes[0], pts, tri, r, (-15, 16, -15.5, 15.5), "whole domain")
    draw(axes[1], pts, tri, r, (-1.5, 2.5, -2.0, 2.0), "around the airfoil")
    fig.suptitle(f"grid-scaled model at {rep_g['final_angle_deg']:.0f} deg (colour: R)")
    fig.savefig(os.path.join(out, "naca0012_domain.png"), dpi=110)
    plt.close(fig)
    print(f"figures written to {out}")


if __name__ == "__main__":
    main()
