#!/usr/bin/python3
"""Plots one leg's hip, knee and ankle flexion through a gait cycle of a BVH walk, from the
Python module (doc/anthropometry.md "Joint angles").

usage: plot_joint_angles.py WALK.bvh [--scale M] [--order XZY] [--side left|right]
                            [--png OUT.png] [--print]

The walk's frames are read as `mbk bag` reads them; each joint's angles are
mb_kinematics.angles of the distal body's rotation relative to the proximal one (the thigh
relative to the pelvis, the first body above it with several children; the shank to the thigh;
the foot to the shank), in --order (default XZY: lateral x, forward z, up y, as CMU's and the
other families' rest poses; the first angle is about the lateral axis). With the lateral axis
to the subject's left, flexion is -angle_1 at the hip, +angle_1 at the knee, and dorsiflexion
-angle_1 at the ankle. The cycle runs from a heel strike to the next of that side, the one
nearest the middle of the recording; heel strikes are the ankle's most forward positions
relative to the pelvis (Zeni, Richards and Higginson 2008). --print writes the cycle's
figures (duration, each angle's range) on standard output.
"""
import argparse
import sys

import numpy as np


def leg(model, side):
    """Indices (0-based) of the pelvis, thigh, shank and foot of one side: the foot is the
    first body named <side>...Foot or <side>...Ankle (any case)."""
    names = [n.lower() for n in model.body_names]
    foot = next((i for i, n in enumerate(names) if side in n and ("foot" in n or "ankle" in n)),
                None)
    if foot is None:
        sys.exit("plot_joint_angles.py: error: no body named %s...Foot or %s...Ankle"
                 % (side, side))
    shank = model.lower[foot] - 1
    thigh = model.lower[shank] - 1
    pelvis = model.lower[thigh] - 1
    children = np.bincount(model.lower, minlength=model.body_count + 1)
    while pelvis > 0 and children[pelvis + 1] < 2:
        pelvis = model.lower[pelvis] - 1
    if min(shank, thigh, pelvis) < 0:
        sys.exit("plot_joint_angles.py: error: the foot has no shank, thigh and pelvis above it")
    return pelvis, thigh, shank, foot


def heel_strikes(origin, pelvis, ankle):
    """Frames where the ankle is farthest forward of the pelvis (horizontal, along the pelvis's
    mean velocity): local maxima more than a third of a median cycle apart."""
    path = origin[:, pelvis]
    forward = path[-1] - path[0]
    forward[1] = 0  # y up
    forward /= np.linalg.norm(forward)
    ahead = (origin[:, ankle] - path) @ forward
    peaks = [i for i in range(1, len(ahead) - 1) if ahead[i] >= ahead[i - 1] and
             ahead[i] > ahead[i + 1] and ahead[i] > 0.5 * ahead.max()]
    return np.array(peaks)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("bvh")
    parser.add_argument("--scale", type=float, default=1.0, help="metres per file unit")
    parser.add_argument("--order", default="XZY")
    parser.add_argument("--side", choices=["left", "right"], default="left")
    parser.add_argument("--png", help="write the figure here instead of showing it")
    parser.add_argument("--print", action="store_true", help="print the cycle's figures")
    args = parser.parse_args()
    import mb_kinematics
    model = mb_kinematics.load(args.bvh, scale=args.scale)
    out = model.recording_kinematics(model.read_recording(args.bvh, scale=args.scale),
                                     outputs=["rotation", "origin"])
    pelvis, thigh, shank, foot = leg(model, args.side)
    rotation = out["rotation"]
    pairs = {"hip": (pelvis, thigh), "knee": (thigh, shank), "ankle": (shank, foot)}
    first = {name: mb_kinematics.angles(
        np.einsum("nji,njk->nik", rotation[:, j], rotation[:, k]), args.order)[:, 0]
        for name, (j, k) in pairs.items()}
    flexion = {"hip": -np.degrees(first["hip"]), "knee": np.degrees(first["knee"]),
               "ankle": -np.degrees(first["ankle"])}
    strikes = heel_strikes(out["origin"], pelvis, foot)
    if len(strikes) < 2:
        sys.exit("plot_joint_angles.py: error: fewer than two heel strikes: no gait cycle")
    middle = len(out["time"]) / 2
    i = int(np.argmin(np.abs((strikes[:-1] + strikes[1:]) / 2 - middle)))
    begin, end = strikes[i], strikes[i + 1]
    t = out["time"][begin:end + 1]
    percent = 100 * (t - t[0]) / (t[-1] - t[0])
    if args.print:
        print("cycle %.3f s to %.3f s (%.3f s)" % (t[0], t[-1], t[-1] - t[0]))
        for name, series in flexion.items():
            s = series[begin:end + 1]
            print("%s flexion %.1f to %.1f deg" % (name, s.min(), s.max()))
    import matplotlib
    if args.png:
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    figure, axes = plt.subplots(3, 1, sharex=True, figsize=(6, 7))
    labels = {"hip": "hip flexion (deg)", "knee": "knee flexion (deg)",
              "ankle": "ankle dorsiflexion (deg)"}
    for ax, name in zip(axes, ("hip", "knee", "ankle")):
        ax.plot(percent, flexion[name][begin:end + 1])
        ax.set_ylabel(labels[name])
        ax.grid(True, alpha=0.3)
    axes[-1].set_xlabel("%% of the gait cycle (%s heel strike to heel strike, %.2f s)"
                        % (args.side, t[-1] - t[0]))
    figure.suptitle("%s: %s leg, %s angles of each segment relative to the one above"
                    % (args.bvh.split("/")[-1], args.side, args.order), fontsize=9)
    figure.tight_layout()
    if args.png:
        figure.savefig(args.png, dpi=90)
    else:
        plt.show()


if __name__ == "__main__":
    main()
