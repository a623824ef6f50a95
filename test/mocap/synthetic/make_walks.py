#!/usr/bin/python3
"""Writes the synthetic walks of this folder: one walk (1.3 m/s along +z, y up, centimetres, 30
frames/s) in the exact file layouts of three BVH families whose own files cannot be shipped here
(their licenses: README.md):

  bandai_layout_walk.bvh   Bandai Namco Research's motion dataset: a static joint_Root and 21
                           joints under it (22 in all: no Chest2), every one with 6 channels
                           (Xposition Yposition Zposition Zrotation Xrotation Yrotation) whose
                           positions repeat its OFFSET, _L/_R names, every End Site at OFFSET
                           0 0 0; the walker 4 s from 4.5 m before the root (its OFFSET) to 0.7 m
  lafan1_layout_walk.bvh   Ubisoft LAFAN1: every joint with 6 channels (... Zrotation Yrotation
                           Xrotation), CMU-like names (LeftUpLeg, LeftToe)
  mixamo_layout_walk.bvh   Mixamo: mixamorig: names, a 6-channel root, 3 rotations elsewhere

The others walk 2 s from the origin. The body: segment lengths of a 1.75 m adult; hips, knees,
shoulders and elbows swing as sinusoids of the gait cycle (1 s), the pelvis bobs 2 cm. Run it to
write the files again; the output is deterministic."""
import math
import os

FPS = 30
FRAMES = 60
SPEED = 130.0  # cm/s along +z
BANDAI_FRAMES = 120
BANDAI_START = -452.2  # cm along z: at the Hips OFFSET, 4.5 m from the static joint_Root
PELVIS = 95.0  # cm above the floor

# name per family: (bandai, lafan1, mixamo); parent; offset (cm); swing amplitude (deg) about X
# and phase (cycles), for the left side; the right side mirrors x and shifts the phase by 0.5.
JOINTS = [
    ("Hips", "Hips", "mixamorig:Hips", None, (0, PELVIS, 0), 0, 0),
    ("Spine", "Spine", "mixamorig:Spine", "Hips", (0, 10, 0), 0, 0),
    ("Chest", "Spine1", "mixamorig:Spine1", "Spine", (0, 15, 0), 0, 0),
    ("Chest2", "Spine2", "mixamorig:Spine2", "Chest", (0, 15, 0), 0, 0),
    ("Neck", "Neck", "mixamorig:Neck", "Chest2", (0, 14, 0), 0, 0),
    ("Head", "Head", "mixamorig:Head", "Neck", (0, 10, 0), 0, 0),
    ("Shoulder_L", "LeftShoulder", "mixamorig:LeftShoulder", "Chest2", (4, 10, 0), 0, 0),
    ("UpperArm_L", "LeftArm", "mixamorig:LeftArm", "Shoulder_L", (14, -4, 0), 20, 0.5),
    ("LowerArm_L", "LeftForeArm", "mixamorig:LeftForeArm", "UpperArm_L", (0, -29, 0), 15, 0.4),
    ("Hand_L", "LeftHand", "mixamorig:LeftHand", "LowerArm_L", (0, -26, 0), 0, 0),
    ("UpperLeg_L", "LeftUpLeg", "mixamorig:LeftUpLeg", "Hips", (9, -4, 0), 25, 0),
    ("LowerLeg_L", "LeftLeg", "mixamorig:LeftLeg", "UpperLeg_L", (0, -43, 0), 30, 0.2),
    ("Foot_L", "LeftFoot", "mixamorig:LeftFoot", "LowerLeg_L", (0, -42, 0), 10, 0.1),
    ("Toes_L", "LeftToe", "mixamorig:LeftToeBase", "Foot_L", (0, -6, 14), 0, 0),
]
END_SITES = {"Head": (0, 18, 0), "Hand_L": (0, -18, 0), "Toes_L": (0, 0, 6)}
# Flexion signs: hips and shoulders swing forward and back, knees and elbows bend one way.
BENDS = {"LowerLeg_L": 1, "LowerArm_L": -1}


def bandai_joints():
    """JOINTS without Chest2, as Bandai Namco's skeleton: its children hang from Chest, their
    OFFSETs lengthened by Chest2's, so that the body keeps its shape."""
    chest2 = next(j for j in JOINTS if j[0] == "Chest2")
    out = []
    for bandai, lafan, mixamo, parent, offset, amp, phase in JOINTS:
        if bandai == "Chest2":
            continue
        if parent == "Chest2":
            parent = "Chest"
            offset = tuple(a + b for a, b in zip(offset, chest2[4]))
        out.append((bandai, lafan, mixamo, parent, offset, amp, phase))
    return out


def skeleton(bandai_root=False):
    """Every joint with both sides: (names, parent name (bandai), offset, amplitude, phase)."""
    out = []
    for bandai, lafan, mixamo, parent, offset, amp, phase in (bandai_joints() if bandai_root
                                                               else JOINTS):
        out.append(((bandai, lafan, mixamo), parent, offset, amp, phase))
        if bandai.endswith("_L"):
            names = (bandai[:-2] + "_R", lafan.replace("Left", "Right"),
                     mixamo.replace("Left", "Right"))
            right_parent = parent[:-2] + "_R" if parent.endswith("_L") else parent
            out.append((names, right_parent, (-offset[0], offset[1], offset[2]), amp,
                        phase + 0.5))
    return out


def angle(name, amp, phase, t):
    """Degrees about X of joint `name` at time t (gait cycle 1 s)."""
    if amp == 0:
        return 0.0
    s = math.sin(2 * math.pi * (t + phase))
    base = name.replace("_R", "_L")
    return amp * (0.5 + 0.5 * s) * BENDS[base] if base in BENDS else amp * s


def write(path, family, channels_of, bandai_root):
    joints = skeleton(bandai_root)
    children = {}
    for j in joints:
        children.setdefault(j[1], []).append(j)
    lines = ["HIERARCHY"]
    columns = []  # per joint in file order: (joint, channels)

    def emit(j, depth, keyword):
        pad = "  " * depth
        names, parent, offset, amp, phase = j
        if parent is None:  # Bandai's Hips: an OFFSET of its own, replaced by its channels
            offset = (0.85, 93.98, -452.2) if bandai_root else (0, 0, 0)
        channels = channels_of(j, keyword)
        lines.append("%s%s %s" % (pad, keyword, names[family]))
        lines.append(pad + "{")
        lines.append("%s  OFFSET %.4f %.4f %.4f" % ((pad,) + tuple(offset)))
        lines.append("%s  CHANNELS %d %s" % (pad, len(channels), " ".join(channels)))
        columns.append((j, channels))
        kids = children.get(names[0], [])
        for k in kids:
            emit(k, depth + 1, "JOINT")
        if not kids:
            end = END_SITES[names[0].replace("_R", "_L")]
            if names[0].endswith("_R"):
                end = (-end[0], end[1], end[2])
            if bandai_root:
                end = (0, 0, 0)
            lines.append(pad + "  End Site")
            lines.append(pad + "  {")
            lines.append("%s    OFFSET %.4f %.4f %.4f" % ((pad,) + tuple(end)))
            lines.append(pad + "  }")
        lines.append(pad + "}")

    hips = children[None][0]
    if bandai_root:
        lines += ["ROOT joint_Root", "{", "  OFFSET 0.0000 0.0000 0.0000",
                  "  CHANNELS 6 " + " ".join(channels_of(None, "ROOT"))]
        emit(hips, 1, "JOINT")
        lines.append("}")
    else:
        emit(hips, 0, "ROOT")
    frames, start = (BANDAI_FRAMES, BANDAI_START) if bandai_root else (FRAMES, 0.0)
    lines += ["MOTION", "Frames: %d" % frames, "Frame Time: %.7f" % (1.0 / FPS)]
    for f in range(frames):
        t = f / FPS
        row = ["0"] * 6 if bandai_root else []
        for j, channels in columns:
            names, parent, offset, amp, phase = j
            if parent is None:
                translation = (0.0, PELVIS + 2 * math.cos(4 * math.pi * t), start + SPEED * t)
            else:
                translation = offset
            for c in channels:
                if c.endswith("position"):
                    row.append("%.4f" % translation["XYZ".index(c[0])])
                elif c == "Xrotation":
                    row.append("%.4f" % angle(names[0], amp, phase, t))
                else:
                    row.append("0.0000")
        lines.append(" ".join(row))
    with open(path, "w") as out:
        out.write("\n".join(lines) + "\n")


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    six_bandai = "Xposition Yposition Zposition Zrotation Xrotation Yrotation".split()
    six_lafan = "Xposition Yposition Zposition Zrotation Yrotation Xrotation".split()
    three = "Zrotation Xrotation Yrotation".split()
    write(os.path.join(here, "bandai_layout_walk.bvh"), 0, lambda j, k: six_bandai, True)
    write(os.path.join(here, "lafan1_layout_walk.bvh"), 1, lambda j, k: six_lafan, False)
    write(os.path.join(here, "mixamo_layout_walk.bvh"), 2,
          lambda j, k: six_lafan if k == "ROOT" else three, False)


if __name__ == "__main__":
    main()
