"""Recordings in memory: read_recording (BVH motion, trajectory CSV, rosbag), Model.states (the offline
estimators, "auto" with standard errors) and Model.recording_kinematics against `mbk bag`'s tidy
CSV of the same recording, number for number; bad input."""
import csv
import os

import numpy as np
import pytest

from conftest import mbk, mbk_path, source

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
        for i, body in enumerate(out.get("body_names", model.body_names)):
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


def test_bad_rows_dropped_as_mbk_bag_drops_them(mbk_kinematics, tmp_path):
    """A recording with a NaN row (dropped as it is read) and a row whose velocity is beyond
    mbk::check_state's 1e50 (dropped as mbk bag computes it): recording_kinematics keeps the rows
    mbk bag writes, number for number, and counts the same drops."""
    import rosbag
    import rospy
    from sensor_msgs.msg import JointState
    model = mbk_kinematics.load(source("test/robots/panda.urdf"))
    mimic = {m["coordinate"] for m in model.mimics}
    names = [n for n in model.coordinate_names if n not in mimic]
    path = str(tmp_path / "bad_rows.bag")
    with rosbag.Bag(path, "w") as bag:
        for i in range(100):
            t = 1 + 0.01 * i
            position = [0.3 * np.sin((1 + 0.2 * j) * t) for j in range(len(names))]
            velocity = [0.3 * (1 + 0.2 * j) * np.cos((1 + 0.2 * j) * t) for j in range(len(names))]
            if i == 40:
                position[2] = float("nan")
            if i == 60:
                velocity[3] = 1e60
            msg = JointState(name=names, position=position, velocity=velocity)
            msg.header.stamp = rospy.Time.from_sec(t)
            bag.write("/joint_states", msg, msg.header.stamp)
    recording = model.read_recording(path)
    out = model.recording_kinematics(recording, estimator="centered_9_4")
    csv_path = str(tmp_path / "bad_rows.csv")
    mbk("bag", path, "--model", source("test/robots/panda.urdf"), "--estimator", "centered_9_4",
        "--csv", csv_path)
    expect_same_as_bag(model, out, tidy_csv(csv_path))
    drops = dict(out["drops"])
    assert drops.pop("bad sample (lengths, duplicates, NaN/Inf)") == 1
    # the row, and the 8 others whose accelerations (the 9-sample window over the velocities)
    # take in its 1e60
    assert drops.pop("state rejected (mbk::check_state)") == 9
    assert set(drops) <= {"too few samples for derivatives"}  # the 9-sample window's ends
    assert len(out["time"]) + sum(out["drops"].values()) == 100
    assert not np.isin(np.round(out["time"], 9), np.round(1.56 + 0.01 * np.arange(9), 9)).any()
    assert not np.isin(np.round(out["time"], 9), [1.4]).any()


def write_arm_bag(model, path, accelerations=False, odometry=False):
    """300 samples of the Panda arm at 100 Hz (positions and velocities) and, at the same stamps,
    its JointAccelerations and a base's nav_msgs/Odometry (driving on and turning)."""
    import rosbag
    import rospy
    from geometry_msgs.msg import Quaternion
    from mb_kinematics_msgs.msg import JointAccelerations
    from nav_msgs.msg import Odometry
    from sensor_msgs.msg import JointState
    mimic = {m["coordinate"] for m in model.mimics}
    names = [n for n in model.coordinate_names if n not in mimic]
    rate = 1 + 0.3 * np.arange(len(names))
    amplitude = np.where([n.startswith("panda_finger") for n in names], 0.01, 0.4)
    with rosbag.Bag(path, "w") as bag:
        for i in range(300):
            t = 1 + 0.01 * i
            stamp = rospy.Time.from_sec(t)
            js = JointState(name=names, position=list(amplitude * np.sin(rate * t)),
                            velocity=list(amplitude * rate * np.cos(rate * t)))
            js.header.stamp = stamp
            bag.write("/joint_states", js, stamp)
            if accelerations:
                a = JointAccelerations(name=names,
                                       acceleration=list(-amplitude * rate ** 2 * np.sin(rate * t)))
                a.header.stamp = stamp
                bag.write("/joint_accelerations", a, stamp)
            if odometry:
                yaw = 0.3 * t
                o = Odometry()
                o.header.stamp, o.header.frame_id, o.child_frame_id = stamp, "odom", "base"
                o.pose.pose.position.x, o.pose.pose.position.y = 0.5 * t, 0.1 * t * t
                o.pose.pose.orientation = Quaternion(0, 0, np.sin(yaw / 2), np.cos(yaw / 2))
                o.twist.twist.linear.x = 0.5 * np.cos(yaw) + 0.2 * t * np.sin(yaw)
                o.twist.twist.linear.y = -0.5 * np.sin(yaw) + 0.2 * t * np.cos(yaw)
                o.twist.twist.angular.z = 0.3
                bag.write("/odom", o, stamp)
    return names


def test_bag_accelerations_as_mbk_bag_reads_them(mbk_kinematics, tmp_path):
    urdf = source("test/robots/panda.urdf")
    model = mbk_kinematics.load(urdf)
    path = str(tmp_path / "arm.bag")
    names = write_arm_bag(model, path, accelerations=True)
    columns = [model.coordinate_names.index(n) for n in names]
    recording = model.read_recording(path, joint_accelerations="/joint_accelerations")
    assert np.isfinite(recording.accelerations[:, columns]).all()
    assert np.isnan(model.read_recording(path).accelerations).all()  # not asked for
    t = 1 + 0.01 * np.arange(300)[:, None]  # as written
    rate = 1 + 0.3 * np.arange(len(names))
    amplitude = np.where([n.startswith("panda_finger") for n in names], 0.01, 0.4)
    assert np.allclose(recording.accelerations[:, columns], -amplitude * rate ** 2 *
                       np.sin(rate * t), rtol=0, atol=1e-12)
    out = model.recording_kinematics(recording)
    assert np.array_equal(out["joint_acceleration"][:, columns], recording.accelerations[:, columns])
    csv_path = str(tmp_path / "arm.csv")
    mbk("bag", path, "--model", urdf, "--joint-accelerations", "/joint_accelerations",
        "--csv", csv_path)
    expect_same_as_bag(model, out, tidy_csv(csv_path))


def test_bag_base_odometry_as_mbk_bag_computes_it(mbk_kinematics, tmp_path):
    urdf = source("test/robots/panda.urdf")
    model = mbk_kinematics.load(urdf)
    path = str(tmp_path / "arm.bag")
    write_arm_bag(model, path, odometry=True)
    recording = model.read_recording(path, base_odometry="odom")
    base = recording.base
    assert base["frame"] == "odom" and base["position"].shape == (300, 3)
    assert np.allclose(base["position"][:, 0], 0.5 * (1 + 0.01 * np.arange(300)), rtol=0,
                       atol=1e-12)
    assert model.read_recording(path).base is None  # not asked for
    out = model.recording_kinematics(recording)
    assert out["body_names"] == [model.frame] + list(model.body_names)
    assert out["origin"].shape == (300, model.body_count + 1, 3)
    assert np.array_equal(out["time"], recording.times)  # as recorded, off the grid by < 1 ns
    csv_path = str(tmp_path / "arm.csv")
    mbk("bag", path, "--model", urdf, "--base-odometry", "odom", "--csv", csv_path)
    expect_same_as_bag(model, out, tidy_csv(csv_path))
    with pytest.raises(ValueError, match="threads only"):
        model.recording_kinematics(recording, outputs=["origin"])
    with pytest.raises(ValueError, match="no topic '/other'"):
        model.read_recording(path, base_odometry="/other")
    with pytest.raises(ValueError, match="need a bag"):
        model.read_recording(source("test/mocap/131_01.bvh"), base_odometry="odom")


def test_rounded_stamps_on_their_grid(mbk_kinematics, tmp_path):
    """An arm moving at 1 to 6 rad/s sampled on an exact 1 kHz grid, its stamps written through
    rospy.Time.from_sec (up to 1 ns early): differentiated on the grid, mbk bag says so, its CSV
    (the streamed path) equals the in-memory one at the recorded stamps, and the bodies'
    accelerations are those of the exact times (test/offline/stamp_rounding_test.cc: 1e4 times
    worse at the stamps as they are)."""
    import subprocess
    import rosbag
    import rospy
    from sensor_msgs.msg import JointState
    urdf = source("test/robots/panda.urdf")
    model = mbk_kinematics.load(urdf)
    mimic = {m["coordinate"] for m in model.mimics}
    names = [n for n in model.coordinate_names if n not in mimic]
    rate = np.linspace(2, 12, len(names))
    amplitude = np.where([n.startswith("panda_finger") for n in names], 0.01, 0.5)
    exact = 10 + np.arange(2000) * 1e-3

    def motion(d):  # (rows, coordinates): the d-th derivative of amplitude sin(rate t + j)
        x = np.outer(exact, rate) + np.arange(len(names))
        return amplitude * rate ** d * np.sin(x + d * np.pi / 2)

    path = str(tmp_path / "grid.bag")
    with rosbag.Bag(path, "w") as bag:
        for t, q in zip(exact, motion(0)):
            msg = JointState(name=names, position=list(q))
            msg.header.stamp = rospy.Time.from_sec(t)
            bag.write("/joint_states", msg, msg.header.stamp)
    stamps = np.array([rospy.Time.from_sec(t).to_sec() for t in exact])
    assert np.abs(stamps - exact).max() > 5e-10  # the rounding is there
    recording = model.read_recording(path)
    assert np.allclose(recording.times, stamps, rtol=0, atol=1e-12)  # as recorded
    grid = recording.grid
    assert grid["moves"] and abs(grid["period"] - 1e-3) < 1e-13 and grid["worst"] <= 1e-9
    out = model.recording_kinematics(recording)
    assert np.array_equal(out["time"], recording.times)
    csv_path = str(tmp_path / "grid.csv")
    done = subprocess.run([mbk_path(), "bag", path, "--model", urdf, "--csv", csv_path],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert "stamps on a uniform grid of 0.001 s" in done.stderr
    rows = tidy_csv(csv_path)
    written = np.array([float(next(iter(r.values()))["stamp"]) for r in rows])
    assert np.allclose(written, stamps, rtol=0, atol=1e-12)  # the stamps as recorded
    expect_same_as_bag(model, out, rows)

    columns = [model.coordinate_names.index(n) for n in names]
    full = [np.zeros((len(exact), model.nq)) for _ in range(3)]
    for d in range(3):
        full[d][:, columns] = motion(d)
    truth = model.kinematics(*full)

    def error(result):
        worst = max(np.abs(result[f] - truth[f]).max() for f in ("alpha", "acceleration"))
        return worst / max(np.abs(truth[f]).max() for f in ("alpha", "acceleration"))

    assert error(out) < 1e-5
    positions = recording.positions.copy()  # from arrays: the same grid
    for m in model.mimics:
        positions[:, model.coordinate_names.index(m["coordinate"])] = (
            m["multiplier"] * positions[:, model.coordinate_names.index(m["source"])] + m["offset"])
    from_arrays = model.recording(recording.times, positions)
    assert from_arrays.grid["moves"]
    assert np.array_equal(model.states(from_arrays)["acceleration"][:, columns],
                          model.states(recording)["acceleration"][:, columns])


def test_csv_times_rounded_to_their_decimals(mbk_kinematics, tmp_path):
    """The arm at 120 Hz, 1 to 6 rad/s, in a trajectory CSV whose times have 6 decimals (up to
    0.5 us off the grid): mbk bag and read_recording differentiate on the grid, as accurate as
    the exact times; the same times given as arrays (no decimals to go by) are not moved."""
    import subprocess
    urdf = source("test/robots/panda.urdf")
    model = mbk_kinematics.load(urdf)
    mimic = {m["coordinate"] for m in model.mimics}
    names = [n for n in model.coordinate_names if n not in mimic]
    columns = [model.coordinate_names.index(n) for n in names]
    rate = np.linspace(2, 12, len(names))
    amplitude = np.where([n.startswith("panda_finger") for n in names], 0.01, 0.5)
    exact = 1 + np.arange(600) / 120

    def motion(d):
        x = np.outer(exact, rate) + np.arange(len(names))
        return amplitude * rate ** d * np.sin(x + d * np.pi / 2)

    path = str(tmp_path / "arm.csv")
    with open(path, "w") as f:
        f.write(",".join(["time"] + names) + "\n")
        for t, q in zip(exact, motion(0)):
            f.write("%.6f," % t + ",".join(repr(float(x)) for x in q) + "\n")
    recording = model.read_recording(path)
    assert recording.grid["moves"] and recording.grid["tolerance"] >= 0.75e-6
    assert np.array_equal(recording.times, np.round(exact, 6))  # as written
    out = model.recording_kinematics(recording)
    csv_path = str(tmp_path / "arm_kinematics.csv")
    done = subprocess.run([mbk_path(), "bag", path, "--model", urdf, "--csv", csv_path],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert "stamps on a uniform grid of 0.008333333" in done.stderr, done.stderr
    expect_same_as_bag(model, out, tidy_csv(csv_path))
    full = [np.zeros((len(exact), model.nq)) for _ in range(3)]
    for d in range(3):
        full[d][:, columns] = motion(d)
    for m in model.mimics:  # the rule, as the recording applies it
        for d in range(3):
            full[d][:, model.coordinate_names.index(m["coordinate"])] = m["multiplier"] * full[d][
                :, model.coordinate_names.index(m["source"])] + (m["offset"] if d == 0 else 0)
    truth = model.kinematics(*full)

    def error(result):
        worst = max(np.abs(result[f] - truth[f]).max() for f in ("alpha", "acceleration"))
        return worst / max(np.abs(truth[f]).max() for f in ("alpha", "acceleration"))

    on_exact = error(model.recording_kinematics(model.recording(exact, full[0])))
    as_arrays = model.recording(recording.times, full[0])
    assert not as_arrays.grid["found"]
    at_stamps = error(model.recording_kinematics(as_arrays))
    print("relative body acceleration error: %.2e on the grid, %.2e on exact times, %.2e at the"
          " 6-decimal times" % (error(out), on_exact, at_stamps))
    assert error(out) < 2 * on_exact
    assert at_stamps > 10 * error(out)


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


def test_a_bvh_recording_takes_its_models_scale(mbk_kinematics):
    """read_recording of a BVH file reads its positions with the scale the model was loaded
    with; another scale would put the pelvis metres off its skeleton: refused."""
    model = mbk_kinematics.load(BVH, scale=SCALE, body_mass=MASS)
    assert model.scale == SCALE
    recording = model.read_recording(BVH)
    assert np.array_equal(recording.positions, model.read_recording(BVH, scale=SCALE).positions)
    with open(BVH) as f:  # the first frame's root position, file units
        first = f.read().split("Frame Time:")[1].split()[1:4]
    assert np.allclose(recording.positions[0, :3], [SCALE * float(x) for x in first], rtol=1e-12)
    with pytest.raises(ValueError, match="loaded with scale 0.056444"):
        model.read_recording(BVH, scale=1.0)
    assert mbk_kinematics.load(BVH).read_recording(BVH).positions[0, 0] == float(first[0])
