#!/usr/bin/env python3
"""Counts the pixels of each arrow color of the BodyKinematics display in a screenshot.

    count_colors.py SHOT.png [--region X0,Y0,X1,Y1]
      ->  one line per quantity: "<name> <pixels>", then "centroid <x> <y>" of them all

With --region, only pixels with X0 <= x < X1 and Y0 <= y < Y1 count; the centroid is over the
whole picture (where the picture's arrows are, -1 -1 when there are none).

Shading scales a color's brightness but keeps its hue, so pixels are matched by hue (within
HUE_TOL degrees of the default color's) among saturated, not too dark ones. The defaults
(mb_kinematics/ros/kinematics_markers.h) are hues that nothing else in the shipped config has:
the grid, background and robot are grey, tf axes red, green and blue.
"""
import colorsys
import subprocess
import sys

HUES = {"velocity": 192, "acceleration": 30, "omega": 300, "alpha": 54}  # (0,204,255) (255,128,0)
HUE_TOL = 9  # degrees                                                   # (230,0,230) (255,230,0)


def main(path, region=None):
    width = int(subprocess.run(["identify", "-format", "%w", path], check=True,
                               stdout=subprocess.PIPE).stdout)
    raw = subprocess.run(["convert", path, "-depth", "8", "rgb:-"], check=True,
                         stdout=subprocess.PIPE).stdout
    x0, y0, x1, y1 = region or (0, 0, width, len(raw) // 3 // width)
    counts = dict.fromkeys(HUES, 0)
    n, sx, sy = 0, 0, 0
    for i in range(0, len(raw) - 2, 3):
        r, g, b = raw[i], raw[i + 1], raw[i + 2]
        hi, lo = max(r, g, b), min(r, g, b)
        if hi < 80 or hi - lo < 0.5 * hi:  # dark or unsaturated
            continue
        h = colorsys.rgb_to_hsv(r / 255, g / 255, b / 255)[0] * 360
        for name, hue in HUES.items():
            if abs((h - hue + 180) % 360 - 180) <= HUE_TOL:
                x, y = (i // 3) % width, (i // 3) // width
                n, sx, sy = n + 1, sx + x, sy + y
                if x0 <= x < x1 and y0 <= y < y1:
                    counts[name] += 1
    for name, count in counts.items():
        print(name, count)
    print("centroid", sx // n if n else -1, sy // n if n else -1)


if __name__ == "__main__":
    if len(sys.argv) == 4 and sys.argv[2] == "--region":
        main(sys.argv[1], [int(v) for v in sys.argv[3].split(",")])
    else:
        main(sys.argv[1])
