#!/usr/bin/env python3
"""Writes a BVH file with the CMU skeleton's names and layout (Hips, LHipJoint, LeftUpLeg, ...,
LowerBack, Spine, Spine1, Neck, Neck1, Head, LeftShoulder, LeftArm, ..., LThumb), in centimetres
(Y up, a T-pose 1.70 m tall), its channels in one rotation order, and smooth made-up motion whose
root rotation crosses +-180 degrees.

  make_cmu_walk.py ZYX 40 60 > cmu_walk.bvh    # test/io/data/cmu_walk.bvh (order, frames, Hz)
  make_cmu_walk.py ZYX 1450 120 > big.bvh      # about 1 MB (doc/speed.md#reading-bvh)
"""
import math
import sys

ORDER = sys.argv[1] if len(sys.argv) > 1 else "ZYX"
FRAMES = int(sys.argv[2]) if len(sys.argv) > 2 else 40
RATE = float(sys.argv[3]) if len(sys.argv) > 3 else 60.0
ROTATIONS = " ".join(a + "rotation" for a in ORDER)
names, out = [], []


def segment(depth, kind, name, offset, children=(), end=None, root=False):
    pad = "  " * depth
    out.append(f"{pad}{kind} {name}")
    out.append(f"{pad}{{")
    out.append(f"{pad}  OFFSET {offset[0]:g} {offset[1]:g} {offset[2]:g}")
    positions = "6 Xposition Yposition Zposition " if root else "3 "
    out.append(f"{pad}  CHANNELS {positions}{ROTATIONS}")
    names.append(name)
    for child in children:
        child(depth + 1)
    if end is not None:
        out.extend([f"{pad}  End Site", f"{pad}  {{",
                    f"{pad}    OFFSET {end[0]:g} {end[1]:g} {end[2]:g}", f"{pad}  }}"])
    out.append(f"{pad}}}")


def joint(name, offset, children=(), end=None):
    return lambda depth: segment(depth, "JOINT", name, offset, children, end)


def leg(side, s):
    return joint(f"{side[0]}HipJoint", (0, 0, 0), [
        joint(f"{side}UpLeg", (9 * s, -6, 0), [
            joint(f"{side}Leg", (0, -42, 0), [
                joint(f"{side}Foot", (0, -42, 0), [
                    joint(f"{side}ToeBase", (0, -6, 12), end=(0, 0, 5))])])])])


def arm(side, s):
    return joint(f"{side}Shoulder", (3 * s, 15, 0), [
        joint(f"{side}Arm", (15 * s, 0, 0), [
            joint(f"{side}ForeArm", (29 * s, 0, 0), [
                joint(f"{side}Hand", (25 * s, 0, 0), [
                    joint(f"{side}FingerBase", (8 * s, 0, 0), end=(6 * s, 0, 0)),
                    joint(f"{side[0]}Thumb", (3 * s, 0, 3), end=(4 * s, 0, 0))])])])])


spine = joint("LowerBack", (0, 2, 0), [joint("Spine", (0, 12, 0), [joint("Spine1", (0, 14, 0), [
    joint("Neck", (0, 18, 0), [joint("Neck1", (0, 5, 0), [joint("Head", (0, 5, 0),
                                                                 end=(0, 18, 0))])]),
    arm("Left", 1), arm("Right", -1)])])])
out.append("HIERARCHY")
segment(0, "ROOT", "Hips", (0, 0, 0), [leg("Left", 1), leg("Right", -1), spine], root=True)
out += ["MOTION", f"Frames: {FRAMES}", f"Frame Time: {1 / RATE:.8f}"]
for f in range(FRAMES):
    t = f / RATE
    row = [3 * math.sin(2 * t), 94 + 2 * math.cos(6 * t), 120 * t,
           5 * math.sin(3 * t + 0.1), 4 * math.cos(5 * t), (170 + 40 * t + 180) % 360 - 180]
    for i in range(len(names) - 1):
        row += [20 * math.sin(4 * t + 0.3 * i), 10 * math.sin(3 * t + 0.7 * i),
                8 * math.cos(5 * t + 0.2 * i)]
    out.append(" ".join(f"{v:.4f}" for v in row))
print("\n".join(out))
