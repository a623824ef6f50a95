"""Shared by the batch tests (ctest python_batch, test/tests.cmake): a small collection of
recordings (the CMU walks of test/mocap, the synthetic BVH walks, a rosbag and a trajectory CSV
of the Panda arm, and a damaged bag), `mbk` and direct `mbk bag` runs to compare with."""
import importlib.util
import json
import os
import shutil
import subprocess

import numpy as np
import pytest

_spec = importlib.util.spec_from_file_location(
    "python_conftest", os.path.join(os.path.dirname(__file__), "..", "python", "conftest.py"))
python_conftest = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(python_conftest)
source, mbk_path = python_conftest.source, python_conftest.mbk_path

PANDA = source("test/robots/panda.urdf")
CMU_SCALE, CMU_MASS = "0.056444", "68.5"
DAMAGED = "arm/damaged.bag"


def write_arm_bag(path, samples=300, phase=0.0):
    """JointState of the Panda arm's 9 coordinates at 100 Hz."""
    import rosbag
    import rospy
    from sensor_msgs.msg import JointState
    names = ["panda_joint%d" % j for j in range(1, 8)] + ["panda_finger_joint1"]
    with rosbag.Bag(path, "w") as bag:
        for i in range(samples):
            t = 1 + 0.01 * i
            msg = JointState(name=names, position=[0.4 * np.sin((1 + 0.3 * j) * t + phase)
                                                   for j in range(7)] + [0.02])
            msg.header.stamp = rospy.Time.from_sec(t)
            bag.write("/joint_states", msg, msg.header.stamp)


def write_arm_csv(path, samples=200):
    names = ["panda_joint%d" % j for j in range(1, 8)] + ["panda_finger_joint1"]
    t = 1 + np.arange(samples) * 0.01  # from 1 s: a bag holds no stamp 0
    q = np.column_stack([0.3 * np.cos((1 + 0.2 * j) * t) for j in range(7)] + [0.01 + 0 * t])
    np.savetxt(path, np.column_stack([t, q]), delimiter=",", header="time," + ",".join(names),
               comments="", fmt="%.17g")


@pytest.fixture(scope="session")
def collection(tmp_path_factory):
    """A folder of recordings: walks/ (BVH, own models), arm/ (a bag, a CSV and a damaged bag:
    the first half of a good one)."""
    root = tmp_path_factory.mktemp("collection") / "recordings"
    (root / "walks" / "synthetic").mkdir(parents=True)
    (root / "arm").mkdir()
    trimmed_walk("131_01.bvh", str(root / "walks" / "131_01.bvh"), 300)
    for name in ("bandai", "lafan1", "mixamo"):
        shutil.copy(source("test/mocap/synthetic/%s_layout_walk.bvh" % name),
                    str(root / "walks" / "synthetic"))
    write_arm_bag(str(root / "arm" / "reach.bag"))
    write_arm_bag(str(root / "arm" / "wave.bag"), phase=1.0)
    write_arm_csv(str(root / "arm" / "trajectory.csv"))
    with open(str(root / "arm" / "reach.bag"), "rb") as f:
        good = f.read()
    with open(str(root / DAMAGED), "wb") as f:
        f.write(good[:len(good) // 2])
    return str(root)


def trimmed_walk(name, path, frames):
    """test/mocap/NAME's first `frames` frames, as a BVH file at `path`."""
    with open(source("test/mocap/" + name)) as f:
        lines = f.read().split("\n")
    motion = lines.index("MOTION")
    lines[motion + 1] = "Frames: %d" % frames
    with open(path, "w") as f:
        f.write("\n".join(lines[:motion + 3 + frames]) + "\n")


@pytest.fixture(scope="session")
def direct_runs(collection, tmp_path_factory):
    """(folder, {recording: its --summary-json}) of direct `mbk bag` runs on the collection."""
    alone = str(tmp_path_factory.mktemp("alone"))
    return alone, {r: direct(collection, r, alone) for r in recordings(collection)}


@pytest.fixture(scope="session")
def walk_template(tmp_path_factory):
    """Six CMU walks (the two trials' first 300 frames, about 0.15 s of mbk bag each, three
    copies each), and the outputs of direct `mbk bag` runs on them."""
    folder = tmp_path_factory.mktemp("template") / "walks"
    (folder / "b").mkdir(parents=True)
    for i in range(3):
        trimmed_walk("131_01.bvh", str(folder / ("a%d.bvh" % i)), 300)
        trimmed_walk("131_03.bvh", str(folder / "b" / ("c%d.bvh" % i)), 300)
    alone = str(tmp_path_factory.mktemp("alone"))
    for relative in recordings(str(folder)):
        direct(str(folder), relative, alone, bag=False)
    return str(folder), output_files(alone)


def recordings(folder):
    """Every recording under `folder`, relative to it."""
    found = []
    for top, _, files in os.walk(folder):
        found += [os.path.relpath(os.path.join(top, f), folder) for f in files
                  if f.endswith((".bag", ".csv", ".bvh"))]
    return sorted(found)


def bag_arguments(relative):
    """mbk bag's options for a recording of the collection, as mbk batch gives them."""
    if relative.endswith(".bvh"):
        return ["--scale", CMU_SCALE, "--body-mass", CMU_MASS]
    return ["--model", PANDA]


def batch(*args, check=None, cwd=None):
    """`mbk batch ARGS...`: (exit status, stdout, stderr)."""
    done = subprocess.run([mbk_path(), "batch"] + list(args), capture_output=True, text=True,
                          cwd=cwd)
    if check is not None:
        assert done.returncode == check, done.stderr
    return done.returncode, done.stdout, done.stderr


def batch_arguments(collection, out_dir, *more):
    """mbk batch's arguments for the collection: both outputs, a bag and a CSV."""
    return [collection, "--out-dir", out_dir, "--model", PANDA, "--scale", CMU_SCALE,
            "--body-mass", CMU_MASS, "--bag", "--csv"] + list(more)


def direct(collection, relative, out_dir, bag=True):
    """One `mbk bag` run on a recording of the collection: its --summary-json (the CSV and its
    side files, and with `bag` the bag, under out_dir, mirrored)."""
    stem = os.path.join(out_dir, os.path.splitext(relative)[0])
    os.makedirs(os.path.dirname(stem), exist_ok=True)
    subprocess.run([mbk_path(), "bag", os.path.join(collection, relative), "--csv",
                    stem + ".csv", "--summary-json", stem + ".json"] + bag_arguments(relative) +
                   (["--out", stem + ".bag"] if bag else []), capture_output=True)
    with open(stem + ".json") as f:
        summary = json.load(f)
    os.remove(stem + ".json")
    return summary


def output_files(out_dir):
    """relative path -> bytes of every output under out_dir (not summary.csv or the records)."""
    files = {}
    for top, dirs, names in os.walk(out_dir):
        dirs[:] = [d for d in dirs if d != ".mbk-batch"]
        for name in names:
            path = os.path.join(top, name)
            if os.path.relpath(path, out_dir) != "summary.csv":
                with open(path, "rb") as f:
                    files[os.path.relpath(path, out_dir)] = f.read()
    return files


def summary_rows(out_dir):
    import csv
    with open(os.path.join(out_dir, "summary.csv"), newline="") as f:
        return list(csv.DictReader(f))
