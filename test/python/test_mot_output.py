"""mbk bag --mot (offline/mot_output.h): an OpenSim Storage file, read here by a reader written
from the format's description (OpenSim's Storage and STOFileAdapter: a name line, key=value
lines, `endheader`, a line of labels starting with `time`, then one line of numbers per row,
split at tabs and spaces): nRows and nColumns count what follows, inDegrees=yes, and every value
is the joint coordinate of the HDF5 file of the same run, angles times 180 / pi, bit for bit."""
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


def test_mot_is_opensim_storage_of_the_coordinates(mbk_kinematics, tmp_path):
    bvh = walk(tmp_path, 250)
    mot, h5_path = str(tmp_path / "walk.mot"), str(tmp_path / "walk.h5")
    status, err = run_bag(bvh, "--scale", SCALE, "--body-mass", MASS, "--mot", mot, "--h5", h5_path)
    assert status == 0, err
    model = mbk_kinematics.load(bvh, scale=float(SCALE), body_mass=float(MASS))
    name, header, labels, rows = read_storage(mot)
    assert name == "Coordinates"
    assert header["version"] == "1" and header["inDegrees"] == "yes"
    assert int(header["nRows"]) == rows.shape[0] == 250
    assert int(header["nColumns"]) == len(labels) == rows.shape[1] == model.nq + 1
    assert labels == ["time"] + list(model.coordinate_names)
    scale = np.where(angle_columns(model), 180.0 / math.pi, 1.0)
    assert (scale != 1).sum() == model.nq - 3  # the hips' translations stay in metres
    with h5py.File(h5_path, "r") as h5:
        assert same(rows[:, 0], h5["time"][...])
        assert same(rows[:, 1:], h5["joint_position"][...] * scale)


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
    mot = str(tmp_path / "arm.mot")
    status, err = run_bag(trajectory, "--model", urdf, "--mot", mot, "--estimator",
                          "centered_9_4")
    assert status == 0, err
    _, header, labels, rows = read_storage(mot)
    assert labels[1:] == list(names) and int(header["nRows"]) == rows.shape[0]
    states = model.states(model.read_recording(trajectory), "centered_9_4")
    assert rows.shape[0] == states["valid"].sum() > 100
    scale = np.where(angle_columns(model), 180.0 / math.pi, 1.0)
    assert (scale == 1).sum() == 2  # the fingers, prismatic
    assert same(rows[:, 1:], states["position"][states["valid"]] * scale)
    for path, message in ((str(tmp_path / "no" / "x.mot"), "cannot create a file beside it"),
                          ("/dev/full", "write failed (No space left on device)")):
        status, err = run_bag(trajectory, "--model", urdf, "--mot", path)
        assert status == 1 and err.count("\n") == 1, err
        assert err.startswith("mbk: error: %s: " % path) and message in err, err
    kept = str(tmp_path / "kept.mot")
    with open(kept, "w") as f:
        f.write("the previous output")
    status, err = run_bag(trajectory, "--model", urdf, "--mot", kept, limit=4096)
    assert status == 1 and "write failed (File too large)" in err, err
    assert open(kept).read() == "the previous output"
    assert not [n for n in os.listdir(str(tmp_path)) if ".mbk-tmp-" in n]
