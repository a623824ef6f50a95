#!/usr/bin/python3
"""scripts/plot_kinematics.py on a small tidy CSV written here: the overview and --walk figures
are written as PNG files, and --walk without system rows, or a body the CSV lacks, is refused
with one line naming the file.

With --bvh (ctest plot_kinematics_bvh: CMAKE_PREFIX_PATH is the devel space, as after sourcing
its setup.bash): the one command from a BVH file runs the workspace's mbk bag and writes the CSV
beside the PNG, the CSV has every body and the whole-body mass center at a human height, and the
PNG is a figure; a BVH file mbk refuses, or no mbk to be found, is one error line."""
import csv
import math
import os
import shutil
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


WALK = os.path.join(os.path.dirname(SCRIPT), "..", "test", "io", "data", "cmu_walk.bvh")


def run(*args, env=None):
    return subprocess.run([sys.executable, SCRIPT] + list(args), capture_output=True, text=True,
                          env=env)


def is_png(path):
    with open(path, "rb") as f:
        return f.read(8) == b"\x89PNG\r\n\x1a\n" and os.path.getsize(path) > 20000


def check_bvh_csv(path, failures):
    """Every frame has the 29 bodies and the system; the mass center is about 1 m up (y)."""
    with open(path) as f:
        rows = list(csv.DictReader(f))
    bodies = {r["body"] for r in rows}
    system = [r for r in rows if r["body"] == "system"]
    if len(rows) != 40 * 30 or len(bodies) != 30 or len(system) != 40:
        failures.append("--bvh CSV: %d rows, %d bodies, %d system rows" %
                        (len(rows), len(bodies), len(system)))
    heights = [float(r["mass_center_y"]) for r in system]
    if not all(0.7 < h < 1.3 for h in heights):
        failures.append("--bvh CSV: mass center heights %s" % heights[:3])
    speeds = [math.hypot(float(r["velocity_x"]), float(r["velocity_z"])) for r in system]
    if not all(math.isfinite(v) and v < 5 for v in speeds) or max(speeds) < 0.1:
        failures.append("--bvh CSV: mass center speeds %s" % speeds[:3])


def find_in_workspace_mbk():
    """The devel space's mbk (CMAKE_PREFIX_PATH, as the ctest sets it)."""
    for prefix in os.environ.get("CMAKE_PREFIX_PATH", "").split(os.pathsep):
        path = os.path.join(prefix, "lib", "mb_kinematics", "mbk")
        if prefix and os.access(path, os.X_OK):
            return path
    sys.exit("FAIL: no mbk in CMAKE_PREFIX_PATH (run as ctest plot_kinematics_bvh)")


def bvh_cases(tmp, failures):
    """The one command from a BVH file: CSV and PNG; its errors."""
    png = os.path.join(tmp, "out", "walk.png")
    os.mkdir(os.path.dirname(png))
    r = run("--bvh", WALK, "--scale", "0.01", "--body-mass", "70", "--png", png)
    csv_path = os.path.join(tmp, "out", "walk.csv")
    if r.returncode != 0 or not os.path.exists(csv_path) or not os.path.exists(png):
        failures.append("--bvh: exit %d, %s" % (r.returncode, r.stderr))
        return
    if "--walk --up y --bodies LeftUpLeg,LeftLeg,LeftFoot" not in r.stderr:
        failures.append("--bvh: not the left thigh, shank and foot: %s" % r.stderr)
    check_bvh_csv(csv_path, failures)
    if not is_png(png):
        failures.append("--bvh: %s is no figure (%d bytes)" % (png, os.path.getsize(png)))
    r = run("--bvh", os.path.join(tmp, "missing.bvh"), "--png", os.path.join(tmp, "m.png"))
    last = r.stderr.strip().splitlines()[-1] if r.stderr.strip() else ""
    if r.returncode == 0 or "missing.bvh: mbk bag failed" not in last or \
            os.path.exists(os.path.join(tmp, "m.png")):
        failures.append("--bvh of a missing file: exit %d, %s" % (r.returncode, r.stderr))
    env = dict(os.environ, CMAKE_PREFIX_PATH="")
    r = run("--bvh", WALK, "--png", os.path.join(tmp, "n.png"), env=env)
    if r.returncode == 0 or "mbk not found" not in r.stderr:
        failures.append("--bvh without mbk: exit %d, %s" % (r.returncode, r.stderr))
    # Installed: the script beside mbk (as catkin_install_python puts it), no workspace needed.
    lib = os.path.join(tmp, "lib")
    os.mkdir(lib)
    shutil.copy(SCRIPT, lib)
    os.symlink(find_in_workspace_mbk(), os.path.join(lib, "mbk"))
    beside = os.path.join(lib, "plot_kinematics.py")
    r = subprocess.run([sys.executable, beside, "--bvh", WALK, "--scale", "0.01", "--png",
                        os.path.join(tmp, "i.png")], capture_output=True, text=True, env=env)
    if r.returncode != 0 or not is_png(os.path.join(tmp, "i.png")):
        failures.append("--bvh beside mbk: exit %d, %s" % (r.returncode, r.stderr))


def segments_cases(tmp, failures):
    """--bvh with --segments on a skeleton whose legs no naming rule finds (femur, tibia, pes):
    the left leg the map names is plotted; a map without it leaves the mass center alone, no
    failure."""
    with open(WALK) as f:
        text = f.read()
    for side, letter in (("Left", "A"), ("Right", "B")):
        for part, bone in (("UpLeg", "Femur"), ("Leg", "Tibia"), ("Foot", "Pes")):
            text = text.replace(" %s%s\n" % (side, part), " %s_%s\n" % (bone, letter))
    bvh = os.path.join(tmp, "bones.bvh")
    with open(bvh, "w") as f:
        f.write(text)
    legs = {"A": "left", "B": "right"}
    both = "".join("%s_%s: %s_%s\n" % (bone, letter, legs[letter], segment)
                   for letter in "AB" for bone, segment in (("Femur", "thigh"),
                                                            ("Tibia", "shank"), ("Pes", "foot")))
    for name, yaml, expected in (
            ("both", both, "--bodies Femur_A,Tibia_A,Pes_A"),
            ("right", "right_foot: {joint: Pes_B}\n", "whole-body mass center alone")):
        path, png = os.path.join(tmp, name + ".yaml"), os.path.join(tmp, name + ".png")
        with open(path, "w") as f:
            f.write(yaml)
        r = run("--bvh", bvh, "--scale", "0.01", "--segments", path, "--png", png)
        if r.returncode != 0 or expected not in r.stderr or not is_png(png):
            failures.append("--segments %s: exit %d, %s" % (name, r.returncode, r.stderr))


def csv_cases(tmp, failures):
    """The figures from a CSV; its refusals."""
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
    r = run(full, "--bodies", "LeftHip", "--scale", "0.01", "--png", os.path.join(tmp, "z.png"))
    if r.returncode == 0 or "go with --bvh" not in r.stderr:
        failures.append("--scale without --bvh: exit %d, %s" % (r.returncode, r.stderr))


def bad_path_cases(tmp, failures):
    """A missing CSV, a CSV that is not UTF-8, a PNG in a missing folder or with an extension no
    image format has: one error line naming it, exit 2 or 1, no traceback."""
    full, latin = os.path.join(tmp, "ok.csv"), os.path.join(tmp, "latin1.csv")
    write_csv(full, ["LeftHip", "system"])
    with open(full, "rb") as f:
        data = f.read()
    with open(latin, "wb") as f:
        f.write(data.replace(b"LeftHip", b"LeftH\xefp\xff", 1))
    cases = [
        ("a missing CSV", [os.path.join(tmp, "none.csv"), "--png", os.path.join(tmp, "a.png")],
         "none.csv"),
        ("a CSV that is not UTF-8", [latin, "--png", os.path.join(tmp, "b.png")], "latin1.csv"),
        ("a PNG in a missing folder",
         [full, "--png", os.path.join(tmp, "no", "such", "c.png")], "no/such"),
        ("an image extension no format has", [full, "--png", os.path.join(tmp, "d.xyz")],
         "d.xyz"),
    ]
    for what, args, named in cases:
        r = run(*args, "--bodies", "LeftHip")
        lines = r.stderr.strip().splitlines()
        if (r.returncode == 0 or "Traceback" in r.stderr or len(lines) != 1
                or named not in lines[0] or "plot_kinematics.py: error:" not in lines[0]):
            failures.append("%s: exit %d, %s" % (what, r.returncode, r.stderr[-400:]))


def incomplete_cases(tmp, failures):
    """Rows of body system_incomplete (mbk bag's name when segments are missing) are the
    system's, and both figures' titles say INCOMPLETE; a complete CSV's do not."""
    import importlib.util
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    spec = importlib.util.spec_from_file_location("plot_kinematics", SCRIPT)
    plot = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(plot)
    for name, incomplete in (("system_incomplete", True), ("system", False)):
        path = os.path.join(tmp, name + ".csv")
        write_csv(path, ["LeftHip", name])
        series = plot.read(path, ["LeftHip", "system"])
        if len(series["system"]["stamp"]) != 20:
            failures.append("%s: %d system rows" % (name, len(series["system"]["stamp"])))
            continue
        for fig in (plot.walk(plt, series, ["LeftHip"], 100, "y", path),
                    plot.overview(plt, series, ["LeftHip"], 100)):
            title = fig._suptitle.get_text() if fig._suptitle else ""
            if ("INCOMPLETE" in title) != incomplete:
                failures.append("%s: title %r" % (name, title))
            plt.close(fig)
        png = os.path.join(tmp, name + ".png")
        r = run(path, "--bodies", "LeftHip", "--walk", "--up", "y", "--png", png)
        if r.returncode != 0 or not os.path.getsize(png) > 1000:
            failures.append("%s --walk: exit %d, %s" % (name, r.returncode, r.stderr))


def main():
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        if "--bvh" in sys.argv:
            bvh_cases(tmp, failures)
            segments_cases(tmp, failures)
        else:
            csv_cases(tmp, failures)
            bad_path_cases(tmp, failures)
            incomplete_cases(tmp, failures)
    for f in failures:
        print("FAIL:", f)
    print("PASS" if not failures else "%d failures" % len(failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
