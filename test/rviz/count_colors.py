#!/usr/bin/env python3
"""Counts the pixels of each arrow color of the BodyKinematics display in a screenshot.

    count_colors.py SHOT.png [--region X0,Y0,X1,Y1]  ->  one line per quantity: "<name> <pixels>"

With --region, only pixels with X0 <= x < X1 and Y0 <= y < Y1 count.

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
    if region:
        x0, y0, x1, y1 = region
        crop = ["-crop", f"{x1 - x0}x{y1 - y0}+{x0}+{y0}", "+repage"]
    else:
        crop = []
    raw = subprocess.run(["convert", path] + crop + ["-depth", "8", "rgb:-"], check=True,
                         stdout=subprocess.PIPE).stdout
    counts = dict.fromkeys(HUES, 0)
    for i in range(0, len(raw) - 2, 3):
        r, g, b = raw[i], raw[i + 1], raw[i + 2]
        hi, lo = max(r, g, b), min(r, g, b)
        if hi < 80 or hi - lo < 0.5 * hi:  # dark or unsaturated
            continue
        h = colorsys.rgb_to_hsv(r / 255, g / 255, b / 255)[0] * 360
        for name, hue in HUES.items():
            if abs((h - hue + 180) % 360 - 180) <= HUE_TOL:
                counts[name] += 1
    for name, n in counts.items():
        print(name, n)


if __name__ == "__main__":
    if len(sys.argv) == 4 and sys.argv[2] == "--region":
        main(sys.argv[1], [int(v) for v in sys.argv[3].split(",")])
    else:
        main(sys.argv[1])
