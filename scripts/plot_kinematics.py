#!/usr/bin/python3
"""Plots the kinematics of chosen bodies over time from a tidy CSV of `mbk bag --csv`.

usage: plot_kinematics.py OUT.csv --bodies NAME[,NAME...] [--png FILE]

Rows: omega, alpha (of the bodies), velocity and acceleration of their mass centers (and of the
system's mass center, body "system", when the CSV has it); columns: x, y, z components in R.
Without --png the figure opens in a window.
"""
import argparse
import csv
import sys

import matplotlib

QUANTITIES = [("omega", "omega (rad/s)"), ("alpha", "alpha (rad/s^2)"),
              ("velocity", "v of mass center (m/s)"),
              ("acceleration", "a of mass center (m/s^2)")]


def read(path, bodies):
    series = {b: {"stamp": []} for b in bodies}
    with open(path) as f:
        reader = csv.DictReader(f)
        if not reader.fieldnames or reader.fieldnames[:2] != ["stamp", "body"]:
            sys.exit("plot_kinematics.py: error: %s: not a tidy CSV of mbk bag "
                     "(header must start with stamp,body)" % path)
        for row in reader:
            s = series.get(row["body"])
            if s is None:
                continue
            s["stamp"].append(float(row["stamp"]))
            for q, _ in QUANTITIES:
                for c in "xyz":
                    cell = row[q + "_" + c]
                    s.setdefault(q + c, []).append(float(cell) if cell else float("nan"))
    return series


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv")
    parser.add_argument("--bodies", required=True, help="comma-separated body names")
    parser.add_argument("--png", help="write the figure here instead of showing it")
    args = parser.parse_args()
    if args.png:
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    bodies = [b for b in args.bodies.split(",") if b]
    series = read(args.csv, bodies + ["system"])
    missing = [b for b in bodies if not series[b]["stamp"]]
    if missing:
        sys.exit("plot_kinematics.py: error: %s: no rows for bodies %s" %
                 (args.csv, ", ".join(missing)))
    shown = bodies + (["system"] if series["system"]["stamp"] and "system" not in bodies else [])
    t0 = min(series[b]["stamp"][0] for b in shown)
    fig, axes = plt.subplots(4, 3, figsize=(14, 11), sharex=True)
    for row, (q, label) in enumerate(QUANTITIES):
        for col, c in enumerate("xyz"):
            ax = axes[row][col]
            for b in shown:
                if b == "system" and q in ("omega", "alpha"):
                    continue
                t = [s - t0 for s in series[b]["stamp"]]
                ax.plot(t, series[b][q + c], label="system mass center" if b == "system" else b,
                        linewidth=1.2, linestyle="--" if b == "system" else "-")
            ax.set_title("%s, %s" % (label, c), fontsize=9)
            ax.grid(True, alpha=0.3)
            if row == 3:
                ax.set_xlabel("time (s) from %.3f" % t0)
    axes[0][0].legend(fontsize=8)
    axes[2][0].legend(fontsize=8)
    fig.tight_layout()
    if args.png:
        fig.savefig(args.png, dpi=90)
    else:
        plt.show()


if __name__ == "__main__":
    main()
