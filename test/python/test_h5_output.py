"""mbk bag --h5 (offline/h5_output.h) read back with h5py: every dataset the tidy CSV of the same
run also has equals it number for number (the CSV's shortest round-trip text reads back to the
same double, -0 as 0; its quaternion is Eigen's of the HDF5 file's rotation, computed here the
same way), the
joint states equal Model.states', names, shapes and attributes; beside --csv and --out, alone,
through mbk batch; and the outputs' safety: an existing file replaced, a missing folder, a folder
that cannot take a file, a full disk (/dev/full, a file-size limit), a signal, each one error
line and nothing partial left."""
import csv
import glob
import os
import resource
import signal
import subprocess
import time

import numpy as np
import pytest

from conftest import mbk_path, source
from test_recordings import write_arm_bag

h5py = pytest.importorskip("h5py")  # python3-h5py: a test dependency (scripts/common.sh)

BVH = source("test/mocap/131_01.bvh")
SCALE, MASS = "0.056444", "68.5"
VECTORS = ["origin", "mass_center", "omega", "alpha", "velocity", "acceleration"]
ERRORS = ["alpha_se", "acceleration_se"]


def run_bag(*args, limit=None):
    """`mbk bag ARGS`: (exit status, stderr). limit: RLIMIT_FSIZE bytes, SIGXFSZ ignored (a
    write past it fails with EFBIG, as one on a full disk with ENOSPC)."""
    def limited():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))
    done = subprocess.run([mbk_path(), "bag"] + list(args), capture_output=True, text=True,
                          preexec_fn=limited if limit else None)
    return done.returncode, done.stderr


def walk(tmp_path, frames=300):
    """test/mocap/131_01.bvh's first `frames` frames."""
    with open(BVH) as f:
        lines = f.read().split("\n")
    motion = lines.index("MOTION")
    lines[motion + 1] = "Frames: %d" % frames
    path = str(tmp_path / "walk.bvh")
    with open(path, "w") as f:
        f.write("\n".join(lines[:motion + 3 + frames]) + "\n")
    return path


def tidy_rows(path):
    """The CSV's rows as text: per stamp, body -> row (dict of cells)."""
    samples = {}
    with open(path) as f:
        for row in csv.DictReader(f):
            samples.setdefault(row["stamp"], {})[row["body"]] = row
    return [samples[s] for s in sorted(samples, key=float)]


def eigen_quaternion(m):
    """Eigen's Quaternion(Matrix3) (Geometry/Quaternion.h, Shoemake's), operation for operation:
    x, y, z, w."""
    t = m[0, 0] + (m[1, 1] + m[2, 2])  # the trace as Eigen's unrolled redux adds it
    q = [0.0] * 4
    if t > 0:
        t = np.sqrt(t + 1.0)
        q[3] = 0.5 * t
        t = 0.5 / t
        q[0] = (m[2, 1] - m[1, 2]) * t
        q[1] = (m[0, 2] - m[2, 0]) * t
        q[2] = (m[1, 0] - m[0, 1]) * t
        return q
    i = 1 if m[1, 1] > m[0, 0] else 0
    i = 2 if m[2, 2] > m[i, i] else i
    j, k = (i + 1) % 3, (i + 2) % 3
    t = np.sqrt(m[i, i] - m[j, j] - m[k, k] + 1.0)
    q[i] = 0.5 * t
    t = 0.5 / t
    q[3] = (m[k, j] - m[j, k]) * t
    q[j] = (m[j, i] + m[i, j]) * t
    q[k] = (m[k, i] + m[i, k]) * t
    return q


def cells(row, name, axes="xyz"):
    """Empty cells (no error bars in that row) as NaN, as the HDF5 file has them."""
    return [float(row["%s_%s" % (name, a)] or "nan") for a in axes]


def same(a, b):
    """The same doubles (NaN where both are NaN; 0 and -0 alike: the CSV writes -0 as 0)."""
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    return a.shape == b.shape and np.array_equal(a, b, equal_nan=True)


def expect_equal_to_csv(h5, rows, errors):
    names = [n.decode() for n in h5["body_names"][...]]
    assert len(rows) == h5["time"].shape[0]
    rotation = h5["rotation"][...]
    data = {name: h5[name][...] for name in VECTORS + (ERRORS if errors else [])}
    for s, sample in enumerate(rows):
        assert "%.9f" % h5["time"][s] == next(iter(sample.values()))["stamp"]
        for b, body in enumerate(names):
            row = sample[body]
            for name in VECTORS + (ERRORS if errors else []):
                assert same(data[name][s, b], cells(row, name)), (s, body, name)
            assert same(eigen_quaternion(rotation[s, b]),
                        [float(row[c]) for c in ("qx", "qy", "qz", "qw")]), (s, body, "rotation")
        if "system" in sample:
            for name in ("mass_center", "velocity", "acceleration"):
                assert same(h5["system_" + name][s], cells(sample["system"], name)), (s, name)


def test_h5_equals_the_csv_bit_for_bit(mbk_kinematics, tmp_path):
    bvh = walk(tmp_path)
    h5_path, csv_path, bag_path = (str(tmp_path / ("walk." + e)) for e in ("h5", "csv", "bag"))
    status, err = run_bag(bvh, "--scale", SCALE, "--body-mass", MASS, "--csv", csv_path,
                          "--h5", h5_path, "--out", bag_path)
    assert status == 0, err
    model = mbk_kinematics.load(bvh, scale=float(SCALE), body_mass=float(MASS))
    n, b, nq = 300, model.body_count, model.nq
    with h5py.File(h5_path, "r") as h5:
        shapes = {"time": (n,), "rotation": (n, b, 3, 3), "system_mass": (n,),
                  "joint_position": (n, nq), "joint_velocity": (n, nq),
                  "joint_acceleration": (n, nq), "joint_velocity_se": (n, nq),
                  "joint_acceleration_se": (n, nq), "body_names": (b,),
                  "coordinate_names": (nq,)}
        shapes.update({name: (n, b, 3) for name in VECTORS + ERRORS})
        shapes.update({name: (n, 3) for name in ("system_mass_center", "system_velocity",
                                                 "system_acceleration", "linear_momentum",
                                                 "angular_momentum")})
        assert {name: h5[name].shape for name in h5} == shapes
        assert [x.decode() for x in h5["body_names"]] == list(model.body_names)
        assert [x.decode() for x in h5["coordinate_names"]] == list(model.coordinate_names)
        assert h5.attrs["frame"] == model.frame and h5.attrs["estimator"] == "auto"
        assert h5.attrs["model_file"] == bvh and h5.attrs["input"] == bvh
        assert h5.attrs["system"] == "system" and h5.attrs["mbk_version"]
        assert h5["omega"].attrs["unit"] == "rad/s" and h5["time"].attrs["unit"] == "s"
        assert h5["rotation"].chunks[1:] == (b, 3, 3) and h5["rotation"].compression is None
        assert np.allclose(h5["system_mass"][...], float(MASS), rtol=1e-12, atol=0)
        expect_equal_to_csv(h5, tidy_rows(csv_path), errors=True)
        states = model.states(model.read_recording(bvh, scale=float(SCALE)))
        assert states["valid"].all()
        for ours, theirs in (("joint_position", "position"), ("joint_velocity", "velocity"),
                             ("joint_acceleration", "acceleration"),
                             ("joint_velocity_se", "velocity_se"),
                             ("joint_acceleration_se", "acceleration_se")):
            assert same(h5[ours][...], states[theirs]), ours
        # Model.kinematics of those states: the same numbers under the same names.
        out = model.kinematics(states["position"], states["velocity"], states["acceleration"])
        for name in ["rotation"] + VECTORS + ["system_mass_center", "system_velocity",
                                              "system_acceleration", "linear_momentum",
                                              "angular_momentum"]:
            assert same(h5[name][...], out[name]), name


def test_h5_alone_compressed_and_in_any_number_of_threads(tmp_path):
    """Uncompressed, whole chunks go straight into the file and the last part through libhdf5's
    chunk cache; compressed, every chunk through it: the same numbers."""
    bvh = walk(tmp_path, 994)
    plain, packed = str(tmp_path / "plain.h5"), str(tmp_path / "packed.h5")
    assert run_bag(bvh, "--scale", SCALE, "--h5", plain, "--threads", "1")[0] == 0
    assert run_bag(bvh, "--scale", SCALE, "--h5", packed, "--h5-compression", "6",
                   "--threads", "2")[0] == 0
    with h5py.File(plain, "r") as a, h5py.File(packed, "r") as b:
        assert set(a) == set(b) and "system_mass" not in a  # no --body-mass: no mass
        rows, chunk = a["rotation"].shape[0], a["rotation"].chunks[0]
        assert rows == 994 and 2 * chunk < rows and rows % chunk  # whole chunks, then a part
        assert b["omega"].compression == "gzip" and b["omega"].compression_opts == 6
        for name in a:
            if a[name].dtype.kind == "f":
                assert same(a[name][...], b[name][...]), name
    assert os.path.getsize(packed) < os.path.getsize(plain)
    again = str(tmp_path / "again.h5")
    assert run_bag(bvh, "--scale", SCALE, "--h5", again, "--threads", "1")[0] == 0
    with open(plain, "rb") as a, open(again, "rb") as b:
        assert a.read() == b.read()  # the same run, the same bytes (no times in the file)
    status, err = run_bag(bvh, "--scale", SCALE, "--h5", plain, "--h5-compression", "10")
    assert status == 1 and "--h5-compression needs a deflate level from 0 to 9" in err


def test_h5_with_a_floating_base(mbk_kinematics, tmp_path):
    urdf = source("test/robots/panda.urdf")
    model = mbk_kinematics.load(urdf)
    bag = str(tmp_path / "arm.bag")
    write_arm_bag(model, bag, odometry=True)
    h5_path, csv_path = str(tmp_path / "arm.h5"), str(tmp_path / "arm.csv")
    status, err = run_bag(bag, "--model", urdf, "--base-odometry", "odom", "--csv", csv_path,
                          "--h5", h5_path)
    assert status == 0, err
    with h5py.File(h5_path, "r") as h5:
        assert h5.attrs["frame"] == "odom" and "alpha_se" not in h5  # no error bars with a base
        assert [x.decode() for x in h5["body_names"]] == [model.frame] + list(model.body_names)
        assert h5["joint_position"].shape[1] == model.nq
        expect_equal_to_csv(h5, tidy_rows(csv_path), errors=False)


def leftovers(path):
    return glob.glob(path + ".mbk-tmp-*")


def test_h5_bad_outputs_one_error_line_nothing_left(tmp_path):
    bvh = walk(tmp_path, 100)
    kept = str(tmp_path / "kept.h5")
    with open(kept, "w") as f:
        f.write("the previous output")
    cases = [
        (str(tmp_path / "no" / "such" / "x.h5"), "cannot create a file beside it"),
        ("/proc/x.h5", "cannot create a file beside it"),  # no file there, even for root
        ("/dev/full", "write (No space left on device)"),  # HDF5 writes as it creates
    ]
    for path, message in cases:
        status, err = run_bag(bvh, "--scale", SCALE, "--h5", path)
        assert status == 1 and err.count("\n") == 1, err
        assert err.startswith("mbk: error: %s: " % path) and message in err, err
    # A file-size limit (as a full disk): the previous file kept, no temporary file left.
    status, err = run_bag(bvh, "--scale", SCALE, "--h5", kept, limit=64 << 10)
    assert status == 1 and err.count("\n") == 1, err
    assert err.startswith("mbk: error: %s: write failed (File too large)" % kept), err
    assert open(kept).read() == "the previous output" and not leftovers(kept)
    # An existing file is replaced when the run succeeds, as the CSV.
    assert run_bag(bvh, "--scale", SCALE, "--h5", kept)[0] == 0
    with h5py.File(kept, "r") as h5:
        assert h5["time"].shape == (100,)
    assert not leftovers(kept)
    status, err = run_bag(bvh, "--scale", SCALE, "--h5", bvh)
    assert status == 1 and "--h5 %s is the same file as the input" % bvh in err


def test_h5_signal_leaves_nothing(tmp_path):
    """SIGTERM while the HDF5 file is written: its temporary file removed, no file at its name."""
    model = source("config/human_body.yaml")
    import mb_kinematics
    names = mb_kinematics.load(model).coordinate_names
    t = 1 + np.arange(50000) * 1e-3  # still written when the signal comes (asserted below)
    path = str(tmp_path / "long.csv")
    columns = [0.3 * np.sin(t * (1 + 0.01 * c)) for c in range(len(names))]
    np.savetxt(path, np.column_stack([t] + columns), delimiter=",", comments="", fmt="%.9g",
               header="time," + ",".join(names))
    out = str(tmp_path / "long.h5")
    child = subprocess.Popen([mbk_path(), "bag", path, "--model", model, "--h5", out,
                              "--estimator", "centered_9_4"], stderr=subprocess.PIPE)
    deadline = time.monotonic() + 60
    while not leftovers(out) and child.poll() is None and time.monotonic() < deadline:
        time.sleep(0.01)
    assert leftovers(out), "no temporary file seen"
    child.send_signal(signal.SIGTERM)
    assert child.wait(60) == -signal.SIGTERM
    child.stderr.close()
    assert not leftovers(out) and not os.path.exists(out)
