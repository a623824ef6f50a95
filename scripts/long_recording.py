#!/usr/bin/env python3
"""A long trajectory CSV for mbk bag's memory and speed figures (doc/speed.md): every movable
joint of a URDF as a slow sine, at a fixed rate, written to stdout or a file. Not committed data:
  scripts/long_recording.py config/human_body.urdf 1000000 /tmp/human_1e6.csv
(1e6 samples of the human body at 1 kHz: about 359 MB)."""
import math
import sys
import xml.etree.ElementTree as ET


def joint_names(urdf):
    return [j.get("name") for j in ET.parse(urdf).getroot().iter("joint")
            if j.get("type") in ("revolute", "continuous", "prismatic")]


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    names, samples = joint_names(sys.argv[1]), int(sys.argv[2])
    rate = 1000.0
    with open(sys.argv[3], "w") as out:
        out.write("time," + ",".join(names) + "\n")
        for i in range(samples):
            t = i / rate
            cells = ["%.6f" % (0.3 * math.sin(2 * math.pi * (0.2 + 0.01 * c) * t + c))
                     for c in range(len(names))]
            out.write("%.3f" % t + "," + ",".join(cells) + "\n")


if __name__ == "__main__":
    main()
