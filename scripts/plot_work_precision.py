#!/usr/bin/python3
"""Log-log plot of error against run time from work_precision.csv (mbk_work_precision).

usage: plot_work_precision.py CSV PNG
Left: kinematics formulations per scene (time per update). Middle: joint-derivative estimators
(time per sample and coordinate), one point per stream. Right: mbk bag's default (auto) against
the best fixed offline estimator chosen in hindsight and the old default, per offline stream.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def default_panel(axes, offline):
    """Per stream: auto, the best fixed estimator in hindsight, the old default centered_0.4s_4."""
    streams = []
    for r in offline:
        if r["scene"] not in streams:
            streams.append(r["scene"])
    error = {(r["method"], r["scene"]): float(r["error"]) for r in offline}
    best = [min(e for (m, s), e in error.items() if s == stream and m != "auto")
            for stream in streams]
    x = range(len(streams))
    axes.plot(x, [error.get(("auto", s), float("nan")) for s in streams], "o", label="default auto")
    axes.plot(x, best, "s", mfc="none", label="best fixed (in hindsight)")
    axes.plot(x, [error.get(("centered_0.4s_4", s), float("nan")) for s in streams], "x",
              label="old default centered_0.4s_4")
    axes.set_xticks(list(x))
    axes.set_xticklabels(streams, rotation=90, fontsize=6)
    axes.set(yscale="log", ylabel="max relative error of the joint acceleration (ends included)",
             title="mbk bag: default vs best fixed vs old default, per stream")
    axes.grid(True, which="both", alpha=0.3)
    axes.legend(fontsize=7)


def main(csv_path, png_path):
    rows = list(csv.DictReader(open(csv_path)))
    formulations = [r for r in rows if "Hz" not in r["scene"]]
    estimators = [r for r in rows if "Hz" in r["scene"]]
    fig, (left, right, third) = plt.subplots(1, 3, figsize=(21, 6))
    markers = "osD^v<>ph*"
    for i, method in enumerate(sorted({r["method"] for r in formulations})):
        pts = [r for r in formulations if r["method"] == method]
        left.scatter([float(r["median_ns"]) / 1e3 for r in pts],
                     [max(float(r["error"]), 1e-20) for r in pts],
                     marker=markers[i % len(markers)], label=method, alpha=0.8)
        for r in pts:
            left.annotate(r["scene"], (float(r["median_ns"]) / 1e3, max(float(r["error"]), 1e-20)),
                          fontsize=6, alpha=0.6)
    left.set(xscale="log", yscale="log", xlabel="median run time per update (us)",
             ylabel="max relative error vs quad-precision reference",
             title="Kinematics: formulation, precision, rotation coordinates")
    left.grid(True, which="both", alpha=0.3)
    left.legend(fontsize=7)
    for i, method in enumerate(sorted({r["method"] for r in estimators})):
        pts = [r for r in estimators if r["method"] == method]
        right.scatter([float(r["median_ns"]) for r in pts], [float(r["error"]) for r in pts],
                      marker=markers[i % len(markers)], label=method, alpha=0.8)
    right.set(xscale="log", yscale="log",
              xlabel="median run time per sample and coordinate (ns)",
              ylabel="max relative error of the joint acceleration",
              title="Joint accelerations estimated from positions (100 Hz, 1 kHz; jitter; noise)")
    right.grid(True, which="both", alpha=0.3)
    right.legend(fontsize=7)
    default_panel(third, [r for r in estimators if "offline" in r["note"]])
    fig.tight_layout()
    fig.savefig(png_path, dpi=110)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
