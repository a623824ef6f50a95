"""Segment frames and joint angles from Python (doc/python.md): the `*_body` outputs are the R
outputs rotated into each body's axes (S0K^T x, numpy against the C++); the `relative_*` outputs
are each body relative to its lower body; `mbk eval --body-axes --relative` gives the same numbers
bit for bit; mb_kinematics.angles gives the joint coordinates back, continues across +-pi and
names bad input."""
import json
import os

import numpy as np
import pytest

from conftest import MODELS, mbk, random_states, source

BODY_AXES = ["omega_body", "alpha_body", "velocity_body", "acceleration_body"]
RELATIVE = ["relative_rotation", "relative_omega", "relative_alpha"]
IN_R = {"omega_body": "omega", "alpha_body": "alpha", "velocity_body": "velocity",
        "acceleration_body": "acceleration"}


def test_new_outputs_are_opt_in(mbk_kinematics):
    model = mbk_kinematics.load(source("config/human_body.urdf"))
    q, v, a = random_states(model, 4, seed=2)
    full = model.kinematics(q, v, a)
    assert not (set(BODY_AXES) | set(RELATIVE)) & set(full)
    assert set(BODY_AXES) | set(RELATIVE) <= set(mbk_kinematics.OPT_IN)
    out = model.kinematics(q, v, a, outputs=BODY_AXES + RELATIVE)
    nb = model.body_count
    assert out["relative_rotation"].shape == (4, nb, 3, 3)
    for name in BODY_AXES + ["relative_omega", "relative_alpha"]:
        assert out[name].shape == (4, nb, 3)
    pose = model.kinematics(q, outputs=["relative_rotation"])
    assert pose["relative_rotation"].shape == (4, nb, 3, 3)
    with pytest.raises(ValueError, match="'alpha_body' needs acceleration"):
        model.kinematics(q, v, outputs=["alpha_body"])


@pytest.mark.parametrize("path", ["config/human_body.urdf", "test/robots/pr2.urdf"])
def test_body_axes_are_the_r_outputs_rotated(mbk_kinematics, path):
    model = mbk_kinematics.load(source(path))
    q, v, a = random_states(model, 20, seed=5)
    out = model.kinematics(q, v, a, outputs=["rotation"] + list(IN_R.values()) + BODY_AXES)
    for body, r_name in IN_R.items():
        rotated = np.einsum("nbji,nbj->nbi", out["rotation"], out[r_name])
        scale = np.maximum(1.0, np.linalg.norm(out[r_name], axis=-1, keepdims=True))
        # The same product in another order of summation: a few ulps of the vector's size.
        assert np.all(np.abs(rotated - out[body]) <= 1e-14 * scale), body


def test_relative_outputs_against_the_lower_body(mbk_kinematics):
    model = mbk_kinematics.load(source("config/human_body.yaml"))
    q, v, a = random_states(model, 20, seed=6)
    out = model.kinematics(q, v, a, outputs=["rotation", "omega", "alpha"] + RELATIVE)
    lower = model.lower
    n = q.shape[0]
    eye = np.broadcast_to(np.eye(3), (n, 1, 3, 3))
    zero = np.zeros((n, 1, 3))
    rot = np.concatenate([eye, out["rotation"]], axis=1)  # index 0: R
    w = np.concatenate([zero, out["omega"]], axis=1)
    al = np.concatenate([zero, out["alpha"]], axis=1)
    for k in range(1, model.body_count + 1):
        j = lower[k - 1]
        sj = rot[:, j]
        rel = np.einsum("nji,njk->nik", sj, rot[:, k])
        dw = w[:, k] - w[:, j]
        w_rel = np.einsum("nji,nj->ni", sj, dw)
        a_rel = np.einsum("nji,nj->ni", sj, al[:, k] - al[:, j] - np.cross(w[:, j], dw))
        assert np.abs(rel - out["relative_rotation"][:, k - 1]).max() <= 1e-14
        assert np.abs(w_rel - out["relative_omega"][:, k - 1]).max() <= 1e-13
        assert np.abs(a_rel - out["relative_alpha"][:, k - 1]).max() <= 1e-12


@pytest.mark.parametrize("path", MODELS[:3])
def test_mbk_eval_gives_the_same_numbers(mbk_kinematics, path, tmp_path):
    model = mbk_kinematics.load(source(path))
    q, v, a = random_states(model, 2, seed=9)
    names = BODY_AXES + RELATIVE
    out = model.kinematics(q, v, a, outputs=names)
    mimic = {m["coordinate"] for m in model.mimics}
    for s in range(2):
        state = {"position": {c: float(x) for c, x in zip(model.coordinate_names, q[s])
                              if c not in mimic},
                 "velocity": {c: float(x) for c, x in zip(model.speed_names, v[s])
                              if c not in mimic},
                 "acceleration": {c: float(x) for c, x in zip(model.speed_names, a[s])
                                  if c not in mimic}}
        file = os.path.join(str(tmp_path), "state.json")
        with open(file, "w") as f:
            json.dump(state, f)
        bodies = json.loads(mbk("eval", "--model", source(path), "--state", file, "--body-axes",
                                "--relative"))["bodies"]
        for i, body in enumerate(bodies):
            for name in names:
                expected = np.asarray(body[name], dtype=np.float64).reshape(out[name][s, i].shape)
                assert np.array_equal(expected, out[name][s, i]), (path, body["name"], name)
    plain = json.loads(mbk("eval", "--model", source(path)))["bodies"][0]
    assert not set(names) & set(plain)


def test_angles_give_the_joint_coordinates_back(mbk_kinematics):
    """The human model's hips are 1-2-3 (XYZ) ball joints with C_k = I: the XYZ angles of their
    relative rotation are their coordinates."""
    model = mbk_kinematics.load(source("config/human_body.yaml"))
    q, v, a = random_states(model, 30, seed=4)
    rel = model.kinematics(q, outputs=["relative_rotation"])["relative_rotation"]
    angles = mbk_kinematics.angles(rel, "XYZ")
    assert angles.shape == (30, model.body_count, 3)
    for joint in ("left_hip", "right_shoulder", "lumbar"):
        k = model.joint_names.index(joint)
        first = model.coordinate_names.index(joint + "/alpha")
        assert np.abs(angles[:, k] - q[:, first:first + 3]).max() <= 1e-13, joint


def test_angles_are_continuous_along_the_first_axis(mbk_kinematics):
    t = np.linspace(0, 1, 101)
    angle = 2.8 + 0.8 * t  # past pi
    c, s = np.cos(angle), np.sin(angle)
    r = np.zeros((101, 3, 3))
    r[:, 0, 0], r[:, 0, 1], r[:, 1, 0], r[:, 1, 1], r[:, 2, 2] = c, -s, s, c, 1
    out = mbk_kinematics.angles(r, "ZYX")
    assert out.shape == (101, 3)
    assert np.abs(out[:, 0] - angle).max() <= 1e-14
    assert np.abs(np.diff(out[:, 0])).max() < 0.01
    one = mbk_kinematics.angles(r[-1], "ZYX")
    assert one.shape == (3,) and abs(one[0] - (angle[-1] - 2 * np.pi)) <= 1e-14
    both = mbk_kinematics.angles(np.stack([r, r], axis=1), ["ZYX", "313"])
    assert both.shape == (101, 2, 3)
    assert np.array_equal(both[:, 0], out)


def test_angles_bad_input(mbk_kinematics):
    r = np.tile(np.eye(3), (4, 2, 1, 1))
    with pytest.raises(ValueError, match="order: .*'XXY'"):
        mbk_kinematics.angles(r, "XXY")
    with pytest.raises(ValueError, match="order: 3 orders"):
        mbk_kinematics.angles(r, ["XYZ", "XYZ", "XYZ"])
    with pytest.raises(ValueError, match=r"rotation: shape \(4, 3\)"):
        mbk_kinematics.angles(np.zeros((4, 3)), "XYZ")
    bad = r.copy()
    bad[2, 1] *= 2
    with pytest.raises(ValueError, match=r"not a rotation matrix at index \(2, 1\)"):
        mbk_kinematics.angles(bad, "XYZ")
    bad = r.copy()
    bad[0, 0, 0, 0] = np.nan
    with pytest.raises(ValueError, match="rotation: not finite"):
        mbk_kinematics.angles(bad, "XYZ")


def test_mbk_bag_columns_are_the_python_outputs(mbk_kinematics, tmp_path):
    """131_01 through `mbk bag --csv --body-axes --angles ORDERS.yaml` and through
    recording_kinematics + angles: the same numbers (the CSV's text reads back exactly)."""
    import csv
    bvh, scale = source("test/mocap/131_01.bvh"), 0.056444
    model = mbk_kinematics.load(bvh, scale=scale, body_mass=68.5)
    orders_file = tmp_path / "orders.yaml"
    orders_file.write_text("default: XZY\nLeftShoulder: YXY\nRightElbow: 312\n")
    path = str(tmp_path / "walk.csv")
    mbk("bag", bvh, "--scale", str(scale), "--body-mass", "68.5", "--csv", path, "--body-axes",
        "--angles", str(orders_file))
    out = model.recording_kinematics(model.read_recording(bvh, scale=scale),
                                     outputs=BODY_AXES + RELATIVE)
    orders = ["YXY" if n == "LeftShoulder" else "ZXY" if n == "RightElbow" else "XZY"
              for n in model.body_names]
    angles = mbk_kinematics.angles(out["relative_rotation"], orders)
    rows = {}
    with open(path) as f:
        for row in csv.DictReader(f):
            rows.setdefault(row["stamp"], {})[row["body"]] = row
    samples = [rows[s] for s in sorted(rows, key=float)]
    assert len(samples) == len(out["time"]) == 994
    for s in (0, 1, 500, 993):
        for i, body in enumerate(model.body_names):
            row = samples[s][body]
            assert row["angle_order"] == orders[i]
            got = np.array([float(row["angle_%d" % j]) for j in (1, 2, 3)])
            assert np.array_equal(got, angles[s, i]), (s, body)
            for name in BODY_AXES + ["relative_omega", "relative_alpha"]:
                got = np.array([float(row[name + "_" + a]) for a in "xyz"])
                assert np.array_equal(got, out[name][s, i]), (s, body, name)
        assert samples[s]["system"]["angle_order"] == ""
    # Continuous: no jump of 2 pi between rows in any angle of any body.
    every = np.array([[[float(samples[s][b]["angle_%d" % j]) for j in (1, 2, 3)]
                       for b in model.body_names] for s in range(len(samples))])
    assert np.array_equal(every, angles)
    assert np.abs(np.diff(every, axis=0)).max() < np.pi


def test_mbk_bag_angles_refused(tmp_path):
    bvh = source("test/mocap/131_01.bvh")
    orders_file = tmp_path / "orders.yaml"
    orders_file.write_text("LeftHip: XZY\n")
    for args, message in ((["--angles", "XZY"], "--csv"), (["--csv", str(tmp_path / "a.csv"),
                          "--angles", str(orders_file)], "no order for"),
                          (["--csv", str(tmp_path / "b.csv"), "--angles", "XXZ"], "XXZ")):
        with pytest.raises(RuntimeError, match=message):
            mbk("bag", bvh, "--scale", "0.056444", "--out", str(tmp_path / "o.bag"), *args)
        assert not os.path.exists(str(tmp_path / "a.csv"))


def test_plot_joint_angles_on_the_cmu_walk(tmp_path):
    """scripts/plot_joint_angles.py on 131_01: a gait cycle of a walking adult's duration, the
    knee flexed (positive, never hyperextended by more than 10 degrees) and most in swing (45 to
    100 degrees: the signs of doc/anthropometry.md), and the figure written."""
    import re
    import subprocess
    import sys
    png = str(tmp_path / "angles.png")
    done = subprocess.run([sys.executable, source("scripts/plot_joint_angles.py"),
                           source("test/mocap/131_01.bvh"), "--scale", "0.056444", "--png", png,
                           "--print"], capture_output=True, text=True, cwd=str(tmp_path))
    assert done.returncode == 0, done.stderr
    duration = float(re.search(r"\(([0-9.]+) s\)", done.stdout).group(1))
    knee = [float(x) for x in re.search(r"knee flexion (\S+) to (\S+) deg",
                                        done.stdout).groups()]
    assert 0.8 < duration < 1.6, done.stdout
    assert -10 < knee[0] < 30 and 45 < knee[1] < 100, done.stdout
    assert os.path.getsize(png) > 10000


def test_load_with_dempster(mbk_kinematics):
    """Dempster's table from Python: the whole-body mass is body_mass, the thigh 10 % of it
    (Winter's Table 4.1), and the mass center differs from de Leva's."""
    bvh = source("test/mocap/131_01.bvh")
    leva = mbk_kinematics.load(bvh, scale=0.056444, body_mass=68.5)
    dempster = mbk_kinematics.load(bvh, scale=0.056444, body_mass=68.5, anthropometry="dempster")
    assert abs(dempster.masses.sum() - 68.5) < 1e-12 * 68.5
    assert abs(dempster.masses[dempster.body_index("LeftHip") - 1] - 6.85) < 1e-12
    q = leva.neutral_position
    g = [m.kinematics(q, outputs=["system_mass_center"])["system_mass_center"]
         for m in (leva, dempster)]
    assert np.linalg.norm(g[1] - g[0]) > 0.01
    with pytest.raises(ValueError, match="neither de_leva nor dempster"):
        mbk_kinematics.load(bvh, scale=0.056444, body_mass=68.5, anthropometry="winter")
    with pytest.raises(ValueError, match="needs body_mass"):
        mbk_kinematics.load(bvh, scale=0.056444, anthropometry="dempster")
