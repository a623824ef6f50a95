#!/usr/bin/python3
"""scripts/plot_kinematics.py on a small tidy CSV written here: the overview and --walk figures
are written as PNG files, and --walk without system rows, or a body the CSV lacks, is refused
with one line naming the file."""
import csv
import os
import subprocess
import sys
import tempfile

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts",
                      "plot_kinematics.py")
HEADER = ("stamp,body,index,lower_body,origin_x,origin_y,origin_z,qx,qy,qz,qw,mass_center_x,"
          "mass_center_y,mass_center_z,omega_x,omega_y,omega_z,alpha_x,alpha_y,alpha_z,"
          "velocity_x,velocity_y,velocity_z,acceleration_x,acceleration_y,"
          "acceleration_z").split(",")


def write_csv(path, bodies):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(HEADER)
        for i in range(20):
            t = 100 + 0.01 * i
            for k, b in enumerate(bodies):
                row = [t, b, k, 0] + [0.1 * i] * 3 + [0, 0, 0, 1] + [0.05 * i, 0.9, 0.01 * i]
                row += [0.2 * k + 0.01 * i] * 12
                w.writerow(row)


def run(*args):
    return subprocess.run([sys.executable, SCRIPT] + list(args), capture_output=True, text=True)


def main():
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        full, no_system = os.path.join(tmp, "walk.csv"), os.path.join(tmp, "nosys.csv")
        write_csv(full, ["LeftHip", "LeftKnee", "system"])
        write_csv(no_system, ["LeftHip", "LeftKnee"])
        for extra in ([], ["--walk", "--up", "y"]):
            png = os.path.join(tmp, "out%d.png" % len(extra))
            r = run(full, "--bodies", "LeftHip,LeftKnee", "--png", png, *extra)
            if r.returncode != 0 or not os.path.getsize(png) > 1000:
                failures.append("%s: exit %d, %s" % (extra, r.returncode, r.stderr))
        r = run(no_system, "--bodies", "LeftHip", "--walk", "--png", os.path.join(tmp, "x.png"))
        if r.returncode == 0 or "no rows for the system" not in r.stderr:
            failures.append("--walk without system rows: exit %d, %s" % (r.returncode, r.stderr))
        r = run(full, "--bodies", "Nobody", "--walk", "--png", os.path.join(tmp, "y.png"))
        if r.returncode == 0 or "no rows for bodies Nobody" not in r.stderr:
            failures.append("unknown body: exit %d, %s" % (r.returncode, r.stderr))
    for f in failures:
        print("FAIL:", f)
    print("PASS" if not failures else "%d failures" % len(failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
