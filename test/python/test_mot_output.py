"""mbk bag --mot (offline/mot_output.h): an OpenSim Storage file, read here by a reader written
from the format's description (OpenSim's Storage and STOFileAdapter: a name line, key=value
lines, `endheader`, a line of labels starting with `time`, then one line of numbers per row,
split at tabs and spaces): nRows and nColumns count what follows, inDegrees=yes; every joint
angle is the CSV's --angles column of the same run times 180 / pi, and with --mot-coordinates
every coordinate is the HDF5 file's, angles times 180 / pi, bit for bit."""
import csv
import math
import os

import numpy as np
import pytest

from conftest import source
from test_h5_output import MASS, SCALE, run_bag, same, walk

h5py = pytest.importorskip("h5py")


def read_storage(path):
    """(name, header keys -> values, labels, rows as an (N, columns) array) of a Storage file;
    AssertionError where it breaks the format."""
    with open(path) as f:
        lines = f.read().split("\n")
    assert lines[-1] == "", "the last line ends with a newline"
    lines.pop()
    name, header, at = None, {}, 0
    while lines[at].strip() != "endheader":
        line = lines[at]
        if "=" in line:
            key, value = line.split("=", 1)
            header[key.strip()] = value.strip()
        else:
            assert name is None, "one name line: %r" % line
            name = line
        at += 1
    labels = lines[at + 1].split()
    assert lines[at + 1] == "\t".join(labels), "labels tab-separated"
    rows = []
    for line in lines[at + 2:]:
        assert line == "\t".join(line.split()), "values tab-separated: %r" % line
        rows.append([float(x) for x in line.split("\t")])
    return name, header, labels, np.array(rows)


def angle_columns(model):
    """Per coordinate: True for an angle (revolute joints' and the 1-2-3 angles of ball, free
    and planar joints; universal joints' alpha, beta)."""
    angles = []
    for name in model.coordinate_names:
        joint, _, suffix = name.rpartition("/")
        if suffix in ("x", "y", "z") and joint:
            angles.append(False)
        elif suffix in ("e1", "e2", "e3", "e4") and joint:
            angles.append(False)
        elif joint:
            angles.append(True)  # alpha, beta, gamma
        else:  # a one-coordinate joint, named after it
            kind = model.joint_types[model.joint_names.index(name)]
            angles.append(kind == "revolute")
    return angles


def csv_angles(path, bodies):
    """(stamps (N,), angles in radians (N, bodies, 3), each body's order) of a tidy CSV's
    --angles columns."""
    with open(path) as f:
        rows = [r for r in csv.DictReader(f) if r["body"] != "system"]
    assert len(rows) % bodies == 0
    stamps = np.array([float(r["stamp"]) for r in rows[::bodies]])
    angles = np.array([[float(r["angle_%d" % i]) for i in (1, 2, 3)] for r in rows])
    return stamps, angles.reshape(-1, bodies, 3), [r["angle_order"] for r in rows[:bodies]]


def angle_labels(body, order):
    """The labels of a body's three angles: <body>_<axis>, numbered for a proper Euler order."""
    if order[0] == order[2]:
        return ["%s_%s%d" % (body, axis, i + 1) for i, axis in enumerate(order)]
    return ["%s_%s" % (body, axis) for axis in order]


def expect_angles(mot, csv_path, model, orders):
    """OUT.mot's angle columns: the CSV's in degrees, under each body's labels in `orders`."""
    name, header, labels, rows = read_storage(mot)
    assert name == "Coordinates"
    assert header["version"] == "1" and header["inDegrees"] == "yes"
    assert int(header["nRows"]) == rows.shape[0] > 100
    assert int(header["nColumns"]) == len(labels) == rows.shape[1]
    bodies = len(model.body_names)
    stamps, angles, csv_orders = csv_angles(csv_path, bodies)
    assert csv_orders == orders
    expected = [l for b, o in zip(model.body_names, orders) for l in angle_labels(b, o)]
    assert labels[:1 + 3 * bodies] == ["time"] + expected
    assert np.abs(rows[:, 0] - stamps).max() <= 5e-10  # the CSV's stamps have 9 decimals
    assert same(rows[:, 1:1 + 3 * bodies], angles.reshape(len(stamps), -1) * (180.0 / math.pi))
    assert np.abs(np.diff(rows[:, 1:1 + 3 * bodies], axis=0)).max() < 180  # continuous
    return labels, rows


def test_mot_is_opensim_storage_of_the_joint_angles(mbk_kinematics, tmp_path):
    """Without --angles: XYZ for every body; --mot-coordinates adds the coordinates."""
    bvh = walk(tmp_path, 250)
    model = mbk_kinematics.load(bvh, scale=float(SCALE), body_mass=float(MASS))
    bodies = len(model.body_names)
    mot, csv_path = str(tmp_path / "walk.mot"), str(tmp_path / "walk.csv")
    status, err = run_bag(bvh, "--scale", SCALE, "--body-mass", MASS, "--mot", mot)
    assert status == 0, err
    status, err = run_bag(bvh, "--scale", SCALE, "--body-mass", MASS, "--csv", csv_path,
                          "--angles", "XYZ")
    assert status == 0, err
    labels, _ = expect_angles(mot, csv_path, model, ["XYZ"] * bodies)
    assert len(labels) == 1 + 3 * bodies

    with_q, h5_path = str(tmp_path / "q.mot"), str(tmp_path / "walk.h5")
    status, err = run_bag(bvh, "--scale", SCALE, "--body-mass", MASS, "--mot", with_q,
                          "--mot-coordinates", "--h5", h5_path)
    assert status == 0, err
    labels, rows = expect_angles(with_q, csv_path, model, ["XYZ"] * bodies)
    assert labels[1 + 3 * bodies:] == list(model.coordinate_names)
    assert len(labels) == 1 + 3 * bodies + model.nq
    scale = np.where(angle_columns(model), 180.0 / math.pi, 1.0)
    assert (scale != 1).sum() == model.nq - 3  # the hips' translations stay in metres
    with h5py.File(h5_path, "r") as h5:
        assert same(rows[:, 0], h5["time"][...])
        assert same(rows[:, 1 + 3 * bodies:], h5["joint_position"][...] * scale)


def test_mot_angles_in_the_orders_of_angles(mbk_kinematics, tmp_path):
    """--angles ORDERS.yaml sets the orders of both files; a proper Euler order's labels are
    numbered."""
    bvh = walk(tmp_path, 200)
    model = mbk_kinematics.load(bvh, scale=float(SCALE), body_mass=float(MASS))
    orders_path = str(tmp_path / "orders.yaml")
    with open(orders_path, "w") as f:
        f.write("default: XZY\nLeftShoulder: YXY\nRightShoulder: ZXZ\n")
    mot, csv_path = str(tmp_path / "walk.mot"), str(tmp_path / "walk.csv")
    status, err = run_bag(bvh, "--scale", SCALE, "--body-mass", MASS, "--mot", mot, "--csv",
                          csv_path, "--angles", orders_path)
    assert status == 0, err
    special = {"LeftShoulder": "YXY", "RightShoulder": "ZXZ"}
    orders = [special.get(b, "XZY") for b in model.body_names]
    labels, _ = expect_angles(mot, csv_path, model, orders)
    assert "LeftShoulder_Y1" in labels and "RightShoulder_Z3" in labels and "Hips_Z" in labels


def test_every_output_holds_the_stamps_the_csv_writes(tmp_path):
    """The OpenSim file's times are the tidy CSV's stamp texts and the HDF5 file's `time` those
    texts read back, for a BVH file's stamps k * 0.0083333 s (its frame time), whose shortest
    texts are not the CSV's 9 decimals."""
    bvh = walk(tmp_path, 100)
    out = {ext: str(tmp_path / ("walk." + ext)) for ext in ("csv", "mot", "h5")}
    status, err = run_bag(bvh, "--scale", SCALE, "--body-mass", MASS, "--csv", out["csv"],
                          "--mot", out["mot"], "--h5", out["h5"])
    assert status == 0, err
    with open(out["csv"]) as f:
        stamps = list(dict.fromkeys(line.split(",", 1)[0] for line in f.readlines()[1:]))
    assert len(stamps) == 100 and stamps[0] == "0.008333300"
    with open(out["mot"]) as f:
        rows = f.read().split("endheader\n", 1)[1].splitlines()[1:]
    assert [r.split("\t", 1)[0] for r in rows] == stamps
    with h5py.File(out["h5"], "r") as h5:
        assert list(h5["time"][:]) == [float(s) for s in stamps]


def test_mot_of_an_arm_and_bad_outputs(mbk_kinematics, tmp_path):
    """A URDF with revolute and prismatic joints (the Panda's fingers): metres stay metres."""
    urdf = source("test/robots/panda.urdf")
    model = mbk_kinematics.load(urdf)
    names = model.coordinate_names
    t = 1 + np.arange(120) * 0.01
    trajectory = str(tmp_path / "arm.csv")
    np.savetxt(trajectory, np.column_stack([t] + [0.01 + 0.3 * np.sin(t + c)
                                                  for c in range(len(names))]),
               delimiter=",", comments="", fmt="%.17g", header="time," + ",".join(names))
    mot, csv_path = str(tmp_path / "arm.mot"), str(tmp_path / "out.csv")
    status, err = run_bag(trajectory, "--model", urdf, "--mot", mot, "--mot-coordinates",
                          "--estimator", "centered_9_4", "--csv", csv_path, "--angles", "ZYX")
    assert status == 0, err
    labels, rows = expect_angles(mot, csv_path, model, ["ZYX"] * len(model.body_names))
    rows = rows[:, 1 + 3 * len(model.body_names):]
    assert labels[1 + 3 * len(model.body_names):] == list(names)
    states = model.states(model.read_recording(trajectory), "centered_9_4")
    assert rows.shape[0] == states["valid"].sum() > 100
    scale = np.where(angle_columns(model), 180.0 / math.pi, 1.0)
    assert (scale == 1).sum() == 2  # the fingers, prismatic
    assert same(rows, states["position"][states["valid"]] * scale)
    for path, message in ((str(tmp_path / "no" / "x.mot"), "cannot create a file beside it"),
                          ("/dev/full", "write failed (No space left on device)")):
        status, err = run_bag(trajectory, "--model", urdf, "--mot", path)
        assert status == 1 and err.count("\n") == 1, err
        assert err.startswith("mbk: error: %s: " % path) and message in err, err
    for options, message in (
            (["--mot-coordinates", "--csv", csv_path], "--mot-coordinates adds columns to the "
             "OpenSim file: give --mot OUT.mot"),
            (["--angles", "XYZ", "--h5", str(tmp_path / "a.h5")], "--angles sets the joint "
             "angles of the CSV and the OpenSim file: give --csv OUT.csv or --mot OUT.mot"),
            (["--mot", mot, "--angles", "XYY"], "XYY")):
        status, err = run_bag(trajectory, "--model", urdf, *options)
        assert status == 1 and err.count("\n") == 1 and message in err, err
    kept = str(tmp_path / "kept.mot")
    with open(kept, "w") as f:
        f.write("the previous output")
    status, err = run_bag(trajectory, "--model", urdf, "--mot", kept, limit=4096)
    assert status == 1 and "write failed (File too large)" in err, err
    assert open(kept).read() == "the previous output"
    assert not [n for n in os.listdir(str(tmp_path)) if ".mbk-tmp-" in n]


def test_two_columns_of_one_label_are_refused(tmp_path):
    """A joint named as a body's angle column (`arm_X`): with --mot-coordinates OpenSim would
    read two columns of one label; refused, nothing written."""
    urdf = str(tmp_path / "two.urdf")
    with open(urdf, "w") as f:
        f.write('<robot name="two"><link name="base"/><link name="arm"/>'
                '<joint name="arm_X" type="revolute"><parent link="base"/><child link="arm"/>'
                '<axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/>'
                '</joint></robot>')
    trajectory = str(tmp_path / "two.csv")
    with open(trajectory, "w") as f:
        f.write("time,arm_X\n" + "".join("%g,%g\n" % (1 + 0.01 * i, 0.01 * i) for i in range(50)))
    mot = str(tmp_path / "two.mot")
    status, err = run_bag(trajectory, "--model", urdf, "--mot", mot)
    assert status == 0, err
    assert read_storage(mot)[2] == ["time", "arm_X", "arm_Y", "arm_Z"]
    os.remove(mot)
    status, err = run_bag(trajectory, "--model", urdf, "--mot", mot, "--mot-coordinates")
    assert status == 1 and err.count("\n") == 1, err
    assert "two columns would be labelled 'arm_X'" in err and err.startswith("mbk: error: " + mot)
    assert not os.path.exists(mot) and not [n for n in os.listdir(str(tmp_path)) if ".mbk-tmp-" in n]
