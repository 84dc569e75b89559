#!/usr/bin/python3
"""Table and bar chart of the largest NACA0012 pitch amplitude per model,
without and with adaptive substepping (scripts/substepping_amplitudes.sh).

usage: plot_substepping_amplitudes.py K TABLE.txt FIGURE.png N1_K0.json N1_KK.json [N2_K0.json N2_KK.json ...]

The JSON files are naca0012_pitch_2d --max-amplitude reports, in pairs
(without, with substepping) per step count.
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    k = int(sys.argv[1])
    table_path, figure_path = sys.argv[2], sys.argv[3]
    reports = [json.load(open(p)) for p in sys.argv[4:]]
    pairs = [(reports[i], reports[i + 1]) for i in range(0, len(reports), 2)]
    models = list(pairs[0][0]["models"])
    res = pairs[0][0]["resolution_deg"]
    lines = [
        "largest pitch amplitude (deg) whose run completes, NACA0012 coarse mesh, bisection to %.1f deg up to 180;" % res,
        "'plain': the paper's method (stop at the first invalid step); 'substeps': an inverting step is retried",
        "as 2, 4, ... up to 2^%d = %d substeps. +: nose up, -: nose down." % (k, 2 ** k),
        "",
    ]
    header = "%-12s" % "model"
    for plain, _ in pairs:
        n = plain["steps"]
        header += " %9s %9s %9s %9s" % ("+ n=%d" % n, "+ sub", "- n=%d" % n, "- sub")
    lines.append(header)
    for m in models:
        row = "%-12s" % m
        for plain, sub in pairs:
            row += " %9.1f %9.1f %9.1f %9.1f" % (plain["models"][m]["positive_deg"], sub["models"][m]["positive_deg"],
                                                 plain["models"][m]["negative_deg"], sub["models"][m]["negative_deg"])
        lines.append(row)
    open(table_path, "w").write("\n".join(lines) + "\n")

    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5), sharey=True)
    groups = len(pairs) * 2
    w = 0.8 / groups
    colors = ["#9ecae1", "#3182bd", "#fdae6b", "#e6550d", "#a1d99b", "#31a354"]
    for ax, key, title in ((axes[0], "positive_deg", "nose up (+)"), (axes[1], "negative_deg", "nose down (-)")):
        for g, (plain, sub) in enumerate(pairs):
            for j, (rep, label) in enumerate(((plain, "%d steps" % plain["steps"]),
                                              (sub, "%d steps, up to %d substeps" % (sub["steps"], 2 ** k)))):
                idx = 2 * g + j
                xs = [i - 0.4 + w * (idx + 0.5) for i in range(len(models))]
                ax.bar(xs, [rep["models"][m][key] for m in models], w, label=label, color=colors[idx % len(colors)])
        ax.set_xticks(list(range(len(models))))
        ax.set_xticklabels(models, rotation=30, ha="right")
        ax.set_title(title)
        ax.set_ylim(0, 190)
        ax.grid(axis="y", alpha=0.3)
    axes[0].set_ylabel("largest completed amplitude (deg)")
    axes[1].legend(loc="upper left", fontsize=8)
    fig.suptitle("NACA0012 pitch: largest amplitude with and without adaptive substepping (180 = search limit)")
    fig.tight_layout()
    fig.savefig(figure_path, dpi=110)


if __name__ == "__main__":
    main()
