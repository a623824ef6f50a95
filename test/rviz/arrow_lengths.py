#!/usr/bin/python3
"""The longest arrow of each color of the BodyKinematics display against the robot's size, on
screenshots of the 3D view (test/rviz/screenshot_test.sh's ARROW_FRACTION).

    arrow_lengths.py SHOT.png [SHOT.png ...] [--region X0,Y0,X1,Y1] [--check LO,HI]
      ->  a line per shot (the robot's size and each color's longest arrow, px), "robot <px>"
          (their median), then per color "<name> <fraction>": the QUANTILE over the shots of
          its longest arrow over the robot's size

The robot's size on screen is the diagonal of the box around the white mass-center spheres
(pixels brighter than 225 in every channel and unsaturated: the shipped config's grid is 200,
its background 115-128, the skeleton 217). An arrow is a connected set of pixels of its color
(count_colors.py's hues); its length the diagonal of its box. With --check, exits 1 unless the
velocity's and the acceleration's fractions are LO to HI.
"""
import subprocess
import sys

import numpy as np
from scipy import ndimage

sys.path.insert(0, __file__.rsplit("/", 1)[0])
from count_colors import HUES, HUE_TOL  # noqa: E402

MIN_ARROW_PIXELS = 20  # smaller sets: specks between other glyphs
# Of the shots' fractions: the longest arrow of a shot varies with the motion's phase and with
# the arrows' angle to the view (0.09 to 0.34 of the robot over 8 shots of Romeo).
QUANTILE = 0.75


def read(path):
    size = subprocess.run(["identify", "-format", "%w %h", path], check=True,
                          stdout=subprocess.PIPE).stdout.split()
    width, height = int(size[0]), int(size[1])
    raw = subprocess.run(["convert", path, "-depth", "8", "rgb:-"], check=True,
                         stdout=subprocess.PIPE).stdout
    return np.frombuffer(raw, np.uint8).reshape(height, width, 3).astype(float)


def hue_degrees(rgb):
    r, g, b = rgb[..., 0], rgb[..., 1], rgb[..., 2]
    hi, lo = rgb.max(-1), rgb.min(-1)
    span = np.where(hi > lo, hi - lo, 1)
    h = np.where(hi == r, (g - b) / span, np.where(hi == g, 2 + (b - r) / span, 4 + (r - g) / span))
    return (60 * h) % 360


def diagonal(mask):
    ys, xs = np.nonzero(mask)
    return float(np.hypot(xs.max() - xs.min(), ys.max() - ys.min())) if len(xs) else 0.0


def measure(rgb):
    """The robot's size and the longest arrow of each color (px) in one shot."""
    hi, lo = rgb.max(-1), rgb.min(-1)
    robot = diagonal((lo > 225) & (hi - lo < 0.15 * hi))
    saturated = (hi >= 80) & (hi - lo >= 0.5 * hi)
    hue = hue_degrees(rgb)
    longest = {}
    for name, h in HUES.items():
        mask = saturated & (np.abs((hue - h + 180) % 360 - 180) <= HUE_TOL)
        labels, n = ndimage.label(mask, structure=np.ones((3, 3)))
        lengths = [diagonal(labels[box] == i + 1)
                   for i, box in enumerate(ndimage.find_objects(labels))
                   if np.count_nonzero(labels[box] == i + 1) >= MIN_ARROW_PIXELS]
        longest[name] = max(lengths, default=0.0)
    return robot, longest


def main(args):
    region, check, shots = None, None, []
    while args:
        arg = args.pop(0)
        if arg == "--region":
            region = [int(v) for v in args.pop(0).split(",")]
        elif arg == "--check":
            check = [float(v) for v in args.pop(0).split(",")]
        else:
            shots.append(arg)
    robots, fractions = [], {name: [] for name in HUES}
    for path in shots:
        rgb = read(path)
        if region:
            x0, y0, x1, y1 = region
            rgb = rgb[y0:y1, x0:x1]
        robot, arrows = measure(rgb)
        robots.append(robot)
        for name, px in arrows.items():
            fractions[name].append(px / robot if robot > 0 else 0.0)
        print("shot %s: robot %.0f, " % (path.rsplit("/", 1)[-1], robot) +
              ", ".join("%s %.0f" % item for item in arrows.items()))
    print("robot %.0f" % np.median(robots))
    ok = min(robots) > 0
    for name, values in fractions.items():
        fraction = float(np.quantile(values, QUANTILE))
        print("%s %.2f" % (name, fraction))
        if check and name in ("velocity", "acceleration"):
            ok = ok and check[0] <= fraction <= check[1]
    return 0 if ok or not check else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
