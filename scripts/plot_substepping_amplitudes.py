#!/usr/bin/python3
"""Table and bar chart of the largest NACA0012 pitch amplitude per model,
without and with adaptive substepping (scripts/substepping_amplitudes.sh).

usage: plot_substepping_amplitudes.py K0.json KK.json K TABLE.txt FIGURE.png
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    without_path, with_path, k, table_path, figure_path = sys.argv[1:6]
    k = int(k)
    without = json.load(open(without_path))
    with_ = json.load(open(with_path))
    models = list(without["models"])
    lines = [
        "largest pitch amplitude (deg) whose %d-step run completes, NACA0012 coarse mesh," % without["steps"],
        "bisection to %.1f deg up to 180 deg; substeps: at most 2^%d = %d per step" % (without["resolution_deg"], k, 2 ** k),
        "",
        "%-12s %12s %12s %12s %12s" % ("model", "+ no substep", "+ substeps", "- no substep", "- substeps"),
    ]
    for m in models:
        a, b = without["models"][m], with_["models"][m]
        lines.append("%-12s %12.1f %12.1f %12.1f %12.1f" % (m, a["positive_deg"], b["positive_deg"],
                                                           a["negative_deg"], b["negative_deg"]))
    open(table_path, "w").write("\n".join(lines) + "\n")

    fig, axes = plt.subplots(1, 2, figsize=(10, 4), sharey=True)
    x = range(len(models))
    w = 0.38
    for ax, key, title in ((axes[0], "positive_deg", "nose up (+)"), (axes[1], "negative_deg", "nose down (-)")):
        ax.bar([i - w / 2 for i in x], [without["models"][m][key] for m in models], w, label="no substepping")
        ax.bar([i + w / 2 for i in x], [with_["models"][m][key] for m in models], w,
               label="up to %d substeps" % 2 ** k)
        ax.set_xticks(list(x))
        ax.set_xticklabels(models, rotation=30, ha="right")
        ax.set_title(title)
        ax.set_ylim(0, 185)
        ax.grid(axis="y", alpha=0.3)
    axes[0].set_ylabel("largest completed amplitude (deg)")
    axes[0].legend(loc="upper left")
    fig.suptitle("NACA0012 pitch, %d steps: largest amplitude with and without adaptive substepping" % without["steps"])
    fig.tight_layout()
    fig.savefig(figure_path, dpi=110)


if __name__ == "__main__":
    main()
