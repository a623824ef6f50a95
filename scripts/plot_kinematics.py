#!/usr/bin/python3
"""Plots the kinematics of chosen bodies over time from a tidy CSV of `mbk bag --csv`.

usage: plot_kinematics.py OUT.csv --bodies NAME[,NAME...] [--png FILE] [--walk [--up AXIS]]
       plot_kinematics.py --bvh WALK.bvh [--scale M] [--body-mass KG] [--sex S] [--png OUT.png]
                          [--csv OUT.csv] [--bodies ...] [--up AXIS] [--segments MAP.yaml]

Rows: omega, alpha (of the bodies), velocity and acceleration of their mass centers (and of the
system's mass center, body "system", when the CSV has it; "system_incomplete" when segments of
the body were not found: the figure's title then says INCOMPLETE); columns: x, y, z in R.
With --walk (for a gait): the whole-body mass center's path seen from above and its height, its
velocity, and the bodies' angular velocities (e.g. one leg's thigh, shank and foot); --up names
R's vertical axis (y for most BVH files). Without --png the figure opens in a window.

With --bvh, one command from a motion capture file to the CSV and the --walk figure: it runs
`mbk bag WALK.bvh --csv OUT.csv` (the installed mbk: beside this script, else found in the
sourced workspaces as rosrun finds it) with --scale, --body-mass (default 70) and --sex, writes
the CSV beside the PNG (OUT.png -> OUT.csv, or --csv), then draws --walk with --up y; without
--bodies, the left thigh, shank and foot: those the --segments map names (left_thigh,
left_shank, left_foot), else the body named Left...Foot or Left...Ankle and its two lower
bodies; with --segments and no left foot either way, the whole-body mass center alone.
"""
import argparse
import csv
import os
import subprocess
import sys

import matplotlib

QUANTITIES = [("omega", "omega (rad/s)"), ("alpha", "alpha (rad/s^2)"),
              ("velocity", "v of mass center (m/s)"),
              ("acceleration", "a of mass center (m/s^2)")]


def read(path, bodies):
    series = {b: {"stamp": []} for b in bodies}
    # mbk bag names the system's rows system_incomplete when segments of the body are missing
    aliased = "system" in series and "system_incomplete" not in series
    if aliased:
        series["system_incomplete"] = series["system"]
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
            s["incomplete"] = row["body"] == "system_incomplete"
            for q in [q for q, _ in QUANTITIES] + ["mass_center"]:
                for c in "xyz":
                    cell = row[q + "_" + c]
                    s.setdefault(q + c, []).append(float(cell) if cell else float("nan"))
    if aliased:
        del series["system_incomplete"]
    return series


INCOMPLETE = ("INCOMPLETE whole body: segments of the table were not found in the skeleton "
              "(mbk's warning names them; --segments FILE maps them)")


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
    if series["system"].get("incomplete"):
        fig.suptitle(INCOMPLETE, color="red")
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
    if system.get("incomplete"):
        fig.suptitle(INCOMPLETE, color="red")
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
        if col == 0 and bodies:
            ax.legend(fontsize=8)
    for ax in fig.axes:
        ax.grid(True, alpha=0.3)
    return fig


def fail(what):
    sys.exit("plot_kinematics.py: error: " + what)


def check_png(plt, path):
    """--png's folder exists and its extension is an image format matplotlib writes."""
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        fail("--png %s: no folder %s" % (path, folder))
    formats = plt.figure().canvas.get_supported_filetypes()
    plt.close("all")
    ext = os.path.splitext(path)[1].lstrip(".").lower()
    if ext not in formats:
        fail("--png %s: not an image format ('%s'; one of %s)" % (path, ext, ", ".join(
            sorted(formats))))


def read_rows(path, bodies):
    """read(), with a missing or unreadable file and text that is not UTF-8 as one error line."""
    try:
        return read(path, bodies)
    except UnicodeDecodeError as e:
        fail("%s: not UTF-8 text (byte %d)" % (path, e.start))
    except OSError as e:
        fail("%s: %s" % (path, e.strerror or e))


def find_mbk():
    """The mbk executable: beside this script (install space), else in the sourced workspaces'
    lib/mb_kinematics (devel space), as rosrun finds it."""
    beside = os.path.join(os.path.dirname(os.path.abspath(__file__)), "mbk")
    if os.access(beside, os.X_OK):
        return beside
    try:
        from catkin.find_in_workspaces import find_in_workspaces
        found = find_in_workspaces(search_dirs=["libexec"], project="mb_kinematics", path="mbk",
                                   first_match_only=True)
    except ImportError:
        found = []
    if not found:
        fail("mbk not found beside this script nor in the workspaces of CMAKE_PREFIX_PATH: "
             "source your workspace's setup.bash first")
    return found[0]


def run_mbk_bag(args):
    """mbk bag on the BVH file, its CSV to args.csv; exits with mbk's error if it fails."""
    command = [find_mbk(), "bag", args.bvh, "--csv", args.csv, "--body-mass",
               args.body_mass or "70"]
    for option in ("scale", "sex", "estimator", "segments"):
        if getattr(args, option):
            command += ["--" + option, getattr(args, option)]
    print(" ".join(command), file=sys.stderr)
    if subprocess.run(command).returncode != 0:
        fail("%s: mbk bag failed (its error above)" % args.bvh)


def mapped_leg(path):
    """The joints a --segments map (doc/anthropometry.md) gives the left thigh, shank and foot,
    those of them it names, in that order."""
    import yaml
    try:
        with open(path) as f:
            entries = yaml.safe_load(f)
    except (OSError, yaml.YAMLError):
        return []  # mbk bag has read it: it said what is wrong
    joints = {}
    for key, value in (entries if isinstance(entries, dict) else {}).items():
        if isinstance(value, dict) and "joint" in value:
            joints[key] = value["joint"]
        elif isinstance(value, str):
            joints[value] = key
    return [str(joints[s]) for s in ("left_thigh", "left_shank", "left_foot") if s in joints]


def default_leg(path, required=True):
    """The left thigh, shank and foot of a tidy CSV: the first body named Left...Foot or
    Left...Ankle (any case, as CMU, Biovision and Mixamo name them) and its two lower bodies;
    without one, an error, or "" when not `required`."""
    names, lower = {}, {}
    with open(path) as f:
        for row in csv.DictReader(f):
            if row["body"] in lower:
                break  # the next sample: every body seen
            names[row["index"]] = row["body"]
            lower[row["body"]] = row["lower_body"]
    def left(name):
        n = name.lower()
        return "left" in n or n.startswith(("l_", "l.")) or n.endswith(("_l", ".l"))
    foot = next((b for b in lower if left(b) and
                 ("foot" in b.lower() or "ankle" in b.lower())), None)
    shank = names.get(lower.get(foot))
    thigh = names.get(lower.get(shank))
    if not thigh and not required:
        print("plot_kinematics.py: %s: no left foot (named or in the --segments map): the "
              "whole-body mass center alone" % path, file=sys.stderr)
        return ""
    if not thigh:
        fail("%s: no left foot (a body named Left...Foot or Left...Ankle under a shank and a "
             "thigh): name the bodies to plot with --bodies" % path)
    return ",".join([thigh, shank, foot])


def bvh_defaults(parser, args):
    """--bvh: the CSV from mbk bag, the --walk figure (y up), the left leg by default."""
    if args.csv:
        parser.error("give the BVH file with --bvh or a CSV, not both (--csv names the "
                     "CSV to write)")
    stem = os.path.splitext(args.png if args.png else os.path.basename(args.bvh))[0]
    args.csv = args.csv_out or stem + ".csv"
    run_mbk_bag(args)
    args.walk = True
    args.up = args.up or "y"
    leg = mapped_leg(args.segments) if args.segments and not args.bodies else []
    args.bodies = args.bodies or ",".join(leg) or default_leg(args.csv, not args.segments)
    print("plot_kinematics.py %s --walk --up %s --bodies %s" % (args.csv, args.up, args.bodies),
          file=sys.stderr)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv", nargs="?", help="a tidy CSV of mbk bag --csv")
    parser.add_argument("--bodies", help="comma-separated body names (required without --bvh)")
    parser.add_argument("--png", help="write the figure here instead of showing it")
    parser.add_argument("--walk", action="store_true",
                        help="whole-body mass center path, height and velocity; the bodies' "
                        "angular velocities")
    parser.add_argument("--up", choices=list("xyz"),
                        help="with --walk: R's vertical axis (default z; y with --bvh)")
    bvh = parser.add_argument_group("from a BVH file (runs mbk bag first)")
    bvh.add_argument("--bvh", help="the motion capture file: implies --walk")
    bvh.add_argument("--csv", dest="csv_out", help="the CSV to write (default: the PNG's "
                     "name with .csv, else the BVH file's name in the current directory)")
    bvh.add_argument("--scale", help="metres per file unit (mbk bag --scale)")
    bvh.add_argument("--body-mass", help="kg (default 70)")
    bvh.add_argument("--sex", choices=["male", "female"])
    bvh.add_argument("--estimator", help="mbk bag --estimator")
    bvh.add_argument("--segments", help="a YAML map joint name: segment (mbk bag --segments)")
    args = parser.parse_args()
    if args.png:
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    if args.png:
        check_png(plt, args.png)
    if args.bvh:
        bvh_defaults(parser, args)
    elif not args.csv or not args.bodies:
        parser.error("give a CSV and --bodies, or --bvh FILE")
    elif any((args.csv_out, args.scale, args.body_mass, args.sex, args.estimator, args.segments)):
        parser.error("--csv, --scale, --body-mass, --sex, --estimator and --segments go with "
                     "--bvh")
    args.up = args.up or "z"
    bodies = [b for b in args.bodies.split(",") if b]
    series = read_rows(args.csv, bodies + ["system"])
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
