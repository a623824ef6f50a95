#!/usr/bin/python3
"""Plots the kinematics of chosen bodies over time from a tidy CSV of `mbk bag --csv`.

usage: plot_kinematics.py OUT.csv --bodies NAME[,NAME...] [--png FILE] [--walk [--up AXIS]]

Rows: omega, alpha (of the bodies), velocity and acceleration of their mass centers (and of the
system's mass center, body "system", when the CSV has it); columns: x, y, z components in R.
With --walk (for a gait): the whole-body mass center's path seen from above and its height, its
velocity, and the bodies' angular velocities (e.g. one leg's thigh, shank and foot); --up names
R's vertical axis (y for most BVH files). Without --png the figure opens in a window.
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
            for q in [q for q, _ in QUANTITIES] + ["mass_center"]:
                for c in "xyz":
                    cell = row[q + "_" + c]
                    s.setdefault(q + c, []).append(float(cell) if cell else float("nan"))
    return series


def overview(plt, series, bodies, t0):
    """The figure of the bodies' omega, alpha, and the velocity and acceleration of G."""
    shown = bodies + (["system"] if series["system"]["stamp"] and "system" not in bodies else [])
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
    return fig


def walk(plt, series, bodies, t0, up, path):
    """The --walk figure: the whole-body mass center (path from above, height, velocity) and
    the bodies' angular velocities."""
    system = series["system"]
    if not system["stamp"]:
        sys.exit("plot_kinematics.py: error: %s: no rows for the system (the whole-body mass "
                 "center); --walk needs a model with masses" % path)
    across = [c for c in "xyz" if c != up]
    t = [s - t0 for s in system["stamp"]]
    fig = plt.figure(figsize=(14, 10))
    grid = fig.add_gridspec(3, 3)
    top = fig.add_subplot(grid[0, 0])
    top.plot(system["mass_center" + across[0]], system["mass_center" + across[1]], linewidth=1.2)
    top.set_aspect("equal", adjustable="datalim")
    top.set_xlabel("%s (m)" % across[0])
    top.set_ylabel("%s (m)" % across[1])
    top.set_title("whole-body mass center seen from above (%s up)" % up, fontsize=9)
    height = fig.add_subplot(grid[0, 1:])
    height.plot(t, system["mass_center" + up], linewidth=1.2)
    height.set_title("whole-body mass center, height %s (m)" % up, fontsize=9)
    for col, c in enumerate("xyz"):
        ax = fig.add_subplot(grid[1, col])
        ax.plot(t, system["velocity" + c], linewidth=1.2)
        ax.set_title("whole-body mass center velocity, %s (m/s)" % c, fontsize=9)
        ax = fig.add_subplot(grid[2, col])
        for b in bodies:
            ax.plot([s - t0 for s in series[b]["stamp"]], series[b]["omega" + c], label=b,
                    linewidth=1.2)
        ax.set_title("segment angular velocity omega, %s (rad/s)" % c, fontsize=9)
        ax.set_xlabel("time (s) from %.3f" % t0)
        if col == 0:
            ax.legend(fontsize=8)
    for ax in fig.axes:
        ax.grid(True, alpha=0.3)
    return fig


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv")
    parser.add_argument("--bodies", required=True, help="comma-separated body names")
    parser.add_argument("--png", help="write the figure here instead of showing it")
    parser.add_argument("--walk", action="store_true",
                        help="whole-body mass center path, height and velocity; the bodies' "
                        "angular velocities")
    parser.add_argument("--up", choices=list("xyz"), default="z",
                        help="with --walk: R's vertical axis (default z)")
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
    t0 = min(series[b]["stamp"][0] for b in bodies + ["system"] if series[b]["stamp"])
    if args.walk:
        fig = walk(plt, series, bodies, t0, args.up, args.csv)
    else:
        fig = overview(plt, series, bodies, t0)
    fig.tight_layout()
    if args.png:
        fig.savefig(args.png, dpi=90)
    else:
        plt.show()


if __name__ == "__main__":
    main()
