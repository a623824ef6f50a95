#!/usr/bin/python3
"""Log-log plot of error against run time from work_precision.csv (mbk_work_precision).

usage: plot_work_precision.py CSV PNG
Left: kinematics formulations per scene (time per update). Right: joint-derivative estimators
(time per sample and coordinate), one point per stream.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(csv_path, png_path):
    rows = list(csv.DictReader(open(csv_path)))
    formulations = [r for r in rows if "Hz" not in r["scene"]]
    estimators = [r for r in rows if "Hz" in r["scene"]]
    fig, (left, right) = plt.subplots(1, 2, figsize=(14, 6))
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
    fig.tight_layout()
    fig.savefig(png_path, dpi=110)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
