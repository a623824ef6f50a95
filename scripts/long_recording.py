#!/usr/bin/env python3
"""A long trajectory CSV for mbk bag's memory and speed figures (doc/speed.md): every movable
joint of a URDF as a slow sine, at a fixed rate, written to a file. Not committed data:
  scripts/long_recording.py config/human_body.urdf 1000000 /tmp/human_1e6.csv [--jitter S]
(1e6 samples of the human body at 1 kHz: about 359 MB). --jitter S: each stamp moved by a normal
deviate of S seconds (seed 1), written to the nanosecond: nearly every interval distinct."""
import math
import random
import sys
import xml.etree.ElementTree as ET


def joint_names(urdf):
    return [j.get("name") for j in ET.parse(urdf).getroot().iter("joint")
            if j.get("type") in ("revolute", "continuous", "prismatic")]


def main():
    if len(sys.argv) not in (4, 6) or (len(sys.argv) == 6 and sys.argv[4] != "--jitter"):
        sys.exit(__doc__)
    names, samples = joint_names(sys.argv[1]), int(sys.argv[2])
    jitter = float(sys.argv[5]) if len(sys.argv) == 6 else 0.0
    stamp = "%.9f" if jitter else "%.3f"
    rng = random.Random(1)
    rate = 1000.0
    with open(sys.argv[3], "w") as out:
        out.write("time," + ",".join(names) + "\n")
        for i in range(samples):
            t = i / rate
            cells = ["%.6f" % (0.3 * math.sin(2 * math.pi * (0.2 + 0.01 * c) * t + c))
                     for c in range(len(names))]
            stamp_t = t + (rng.gauss(0, jitter) if jitter else 0)
            out.write(stamp % stamp_t + "," + ",".join(cells) + "\n")


if __name__ == "__main__":
    main()
