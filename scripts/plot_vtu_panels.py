#!/usr/bin/python3
"""Side-by-side pictures of 2D .vtu files written by spring-motion (or the
demos), each triangle coloured by its equiangle skewness R: what ParaView
shows when colouring by 'skewness'. Used for docs/figures/cli_walkthrough.png
(see docs/cli.md for the commands).

usage: plot_vtu_panels.py OUT.png X0,X1,Y0,Y1 FILE.vtu:TITLE [FILE.vtu:TITLE ...]
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import meshio  # noqa: E402
import numpy as np  # noqa: E402

out, window, panels = sys.argv[1], [float(v) for v in sys.argv[2].split(",")], sys.argv[3:]
fig, axes = plt.subplots(1, len(panels), figsize=(4.2 * len(panels), 3.6), constrained_layout=True)
axes = np.atleast_1d(axes)
for ax, panel in zip(axes, panels):
    path, title = panel.split(":", 1)
    mesh = meshio.read(path)
    tri = mesh.cells_dict["triangle"]
    r = np.asarray(mesh.cell_data_dict["skewness"]["triangle"]).reshape(-1)
    p = mesh.points
    im = ax.tripcolor(p[:, 0], p[:, 1], tri, facecolors=r, vmin=0, vmax=1, cmap="viridis",
                      edgecolors="k", linewidth=0.15)
    ax.set_xlim(window[0], window[1])
    ax.set_ylim(window[2], window[3])
    ax.set_aspect("equal")
    ax.set_title("%s\nmax R %.3f" % (title, r.max()), fontsize=9)
    ax.tick_params(labelsize=7)
fig.colorbar(im, ax=axes.tolist(), shrink=0.8, label="equiangle skewness R")
fig.savefig(out, dpi=110)
print("wrote", out)
