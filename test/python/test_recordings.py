"""Recordings in memory: read_recording (BVH motion, trajectory CSV, rosbag), Model.states (the offline
estimators, "auto" with standard errors) and Model.recording_kinematics against `mbk bag`'s tidy
CSV of the same recording, number for number; bad input."""
import csv
import os

import numpy as np
import pytest

from conftest import mbk, source

BVH = source("test/mocap/131_01.bvh")
SCALE, MASS = 0.056444, 68.5
FIELDS = {"origin": "origin", "mass_center": "mass_center", "omega": "omega", "alpha": "alpha",
          "velocity": "velocity", "acceleration": "acceleration"}


def tidy_csv(path):
    """mbk bag's tidy CSV: per stamp, body name -> row."""
    samples = {}
    with open(path) as f:
        for row in csv.DictReader(f):
            samples.setdefault(row["stamp"], {})[row["body"]] = row
    return [samples[s] for s in sorted(samples, key=float)]


def vector(row, name):
    return np.array([float(row["%s_%s" % (name, a)]) for a in "xyz"])


def expect_same_as_bag(model, out, rows):
    assert len(rows) == len(out["time"])
    for s, sample in enumerate(rows):
        for i, body in enumerate(model.body_names):
            for ours, theirs in FIELDS.items():
                assert np.array_equal(out[ours][s, i], vector(sample[body], theirs)), (
                    "sample %d body %s %s: %s vs %s" % (s, body, ours, out[ours][s, i],
                                                        vector(sample[body], theirs)))
        if "system" in sample:
            for ours, theirs in (("system_mass_center", "mass_center"),
                                 ("system_velocity", "velocity"),
                                 ("system_acceleration", "acceleration")):
                assert np.array_equal(out[ours][s], vector(sample["system"], theirs)), ours


def test_bvh_walk_as_mbk_bag_computes_it(mbk_kinematics, tmp_path):
    model = mbk_kinematics.load(BVH, scale=SCALE, body_mass=MASS)
    recording = model.read_recording(BVH, scale=SCALE)
    assert recording.positions.shape == (994, model.nq) and not recording.drops
    assert np.isnan(recording.velocities).all()  # BVH records positions only
    out = model.recording_kinematics(recording)
    path = str(tmp_path / "walk.csv")
    mbk("bag", BVH, "--scale", str(SCALE), "--body-mass", str(MASS), "--csv", path)
    expect_same_as_bag(model, out, tidy_csv(path))
    states = model.states(recording)
    assert states["valid"].all()
    assert (states["velocity_se"] > 0).any() and (states["acceleration_se"] >= 0).all()


def test_trajectory_csv_and_arrays(mbk_kinematics, tmp_path):
    model = mbk_kinematics.load(source("test/robots/panda.urdf"))
    mimic = {m["coordinate"] for m in model.mimics}
    names = [n for n in model.coordinate_names if n not in mimic]
    t = np.arange(1, 401) * 0.01
    q = np.array([0.3 * np.sin((1 + 0.2 * i) * t) for i in range(len(names))]).T
    path = str(tmp_path / "arm.csv")
    with open(path, "w") as f:
        f.write(",".join(["time"] + names) + "\n")
        for row in np.column_stack([t, q]):
            f.write(",".join(repr(float(x)) for x in row) + "\n")
    recording = model.read_recording(path)
    assert np.array_equal(recording.times, t)
    out = model.recording_kinematics(recording, estimator="centered_9_4")
    bag = str(tmp_path / "arm_kinematics.csv")
    mbk("bag", path, "--model", source("test/robots/panda.urdf"), "--estimator", "centered_9_4",
        "--csv", bag)
    expect_same_as_bag(model, out, tidy_csv(bag))
    full = np.tile(model.neutral_position, (len(t), 1))
    full[:, [model.coordinate_names.index(n) for n in names]] = q
    for m in model.mimics:  # the rule, as the recording applies it
        full[:, model.coordinate_names.index(m["coordinate"])] = (
            m["multiplier"] * full[:, model.coordinate_names.index(m["source"])] + m["offset"])
    from_arrays = model.states(model.recording(t, full), estimator="centered_9_4")
    from_file = model.states(recording, estimator="centered_9_4")
    for name in ("position", "velocity", "acceleration"):
        assert np.array_equal(from_arrays[name], from_file[name]), name


def test_bag_as_mbk_bag_computes_it(mbk_kinematics, tmp_path):
    import rosbag
    import rospy
    from sensor_msgs.msg import JointState
    model = mbk_kinematics.load(source("test/robots/panda.urdf"))
    names = list(model.coordinate_names[:7])  # the arm; the fingers in every other message
    path = str(tmp_path / "arm.bag")
    with rosbag.Bag(path, "w") as bag:
        for i in range(300):
            t = 1 + 0.01 * i
            msg = JointState(name=names, position=[0.4 * np.sin((1 + 0.3 * j) * t)
                                                   for j in range(7)])
            if i % 2 == 0:
                msg.name = names + ["panda_finger_joint1"]
                msg.position = list(msg.position) + [0.02 + 0.01 * np.sin(t)]
            msg.header.stamp = rospy.Time.from_sec(t)
            bag.write("/joint_states", msg, msg.header.stamp)
    recording = model.read_recording(path)
    assert recording.positions.shape == (300, model.nq)
    assert np.isnan(recording.positions[1, model.coordinate_names.index("panda_finger_joint1")])
    out = model.recording_kinematics(recording)
    csv_path = str(tmp_path / "arm.csv")
    mbk("bag", path, "--model", source("test/robots/panda.urdf"), "--csv", csv_path)
    expect_same_as_bag(model, out, tidy_csv(csv_path))
    states = model.states(recording)
    finger = model.coordinate_names.index("panda_finger_joint1")
    se = states["velocity_se"][:, finger]  # the fingers are in every other sample only:
    assert np.all(np.isfinite(se)) and np.all(se > 0)
    assert np.array_equal(se[1::2], se[0::2])  # a row without them holds the last sample's
    with pytest.raises(ValueError, match="topic"):
        model.read_recording(path, joint_states="/other")


def test_bad_recordings(mbk_kinematics, tmp_path):
    model = mbk_kinematics.load(source("test/robots/panda.urdf"))
    t = np.array([0.0, 0.1, 0.1, 0.3])
    q = np.zeros((4, model.nq))
    with pytest.raises(ValueError, match="times: not increasing at row 2"):
        model.recording(t, q)
    with pytest.raises(ValueError, match="times, positions: shapes"):
        model.recording(t, q[:, 1:])
    q[1, 2] = np.nan
    with pytest.raises(ValueError, match="not finite"):
        model.recording(np.arange(4.0), q)
    recording = model.recording(np.arange(4.0), np.zeros((4, model.nq)))
    with pytest.raises(ValueError, match="estimator"):
        model.states(recording, estimator="median")
    with pytest.raises(TypeError, match="recording: a Recording"):
        model.states(np.zeros((4, model.nq)))
    with pytest.raises(ValueError, match="not a recording"):
        model.read_recording(str(tmp_path / "run.txt"))
    with pytest.raises(ValueError, match="missing.csv"):
        model.read_recording(str(tmp_path / "missing.csv"))
