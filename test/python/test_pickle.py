"""Models and recordings pickle as their source and options (doc/python.md, Pickling): the copy
computes the same numbers, bit for bit; multiprocessing (spawn) and a Dask LocalCluster take a
model's method and a recording as arguments; copy and deepcopy give the (immutable) object."""
import copy
import multiprocessing
import os
import pickle
import shutil

import numpy as np
import pytest

from conftest import random_states, source

BVH = source("test/mocap/131_01.bvh")
SCALE, MASS = 0.056444, 68.5


def same_kinematics(a, b, samples=5):
    q, v, acc = random_states(a, samples, seed=3)
    ours, theirs = a.kinematics(q, v, acc), b.kinematics(q, v, acc)
    assert ours.keys() == theirs.keys()
    for name in ours:
        np.testing.assert_array_equal(ours[name], theirs[name], err_msg=name)


@pytest.mark.parametrize("how", ["file", "text", "bvh"])
def test_model_pickles_as_its_source(mbk_kinematics, how):
    if how == "file":
        model = mbk_kinematics.load(source("test/robots/panda.urdf"))
    elif how == "text":
        with open(source("config/human_body.yaml")) as f:
            model = mbk_kinematics.load(f.read())
    else:
        model = mbk_kinematics.load(BVH, scale=SCALE, body_mass=MASS)
    again = pickle.loads(pickle.dumps(model))
    assert again is not model
    for name in ("body_names", "coordinate_names", "speed_names", "joint_types", "frame"):
        assert getattr(again, name) == getattr(model, name), name
    np.testing.assert_array_equal(again.masses, model.masses)  # the BVH's options kept
    same_kinematics(model, again)
    assert copy.copy(model) is model and copy.deepcopy(model) is model  # immutable
    assert copy.deepcopy({"m": model})["m"] is model


def test_relative_path_pickles_as_the_absolute_one(mbk_kinematics, tmp_path, monkeypatch):
    monkeypatch.chdir(source("config"))
    data = pickle.dumps(mbk_kinematics.load("ten_body.yaml"))
    monkeypatch.chdir(str(tmp_path))
    assert pickle.loads(data).body_names[:2] == ("B1", "B2")


def test_a_changed_model_file_is_refused(mbk_kinematics, tmp_path):
    path = str(tmp_path / "panda.urdf")
    shutil.copy(source("test/robots/panda.urdf"), path)
    data = pickle.dumps(mbk_kinematics.load(path))
    with open(path, "a") as f:
        f.write("\n<!-- edited -->\n")
    with pytest.raises(ValueError, match="panda.urdf: the model file changed since the model "
                                         "was pickled"):
        pickle.loads(data)
    os.remove(path)
    with pytest.raises(FileNotFoundError, match="no such file"):
        pickle.loads(data)


def test_recordings_pickle_as_their_source(mbk_kinematics):
    model = mbk_kinematics.load(BVH, scale=SCALE, body_mass=MASS)
    read = model.read_recording(BVH, scale=SCALE)
    t = np.arange(6) / 100.0
    q = np.tile(model.neutral_position, (6, 1))
    q[:, 0] = np.sin(t)
    arrays = model.recording(t, q)
    q[:] = 7  # the caller's array changes after: the recording (and its pickle) does not
    for recording in (read, arrays):
        again = pickle.loads(pickle.dumps(recording))
        assert again is not recording and repr(again) == repr(recording)
        for name in ("times", "positions", "velocities", "accelerations"):
            np.testing.assert_array_equal(getattr(again, name), getattr(recording, name))
        assert again.drops == recording.drops and again.grid == recording.grid
        ours, theirs = model.states(recording), model.states(again)
        for name in ("position", "velocity", "acceleration"):
            np.testing.assert_array_equal(ours[name], theirs[name])
        assert copy.deepcopy(recording) is recording
    assert arrays.positions[0, 0] == 0 and arrays.positions[1, 0] == np.sin(0.01)


def test_multiprocessing_spawn(mbk_kinematics):
    model = mbk_kinematics.load(source("config/human_body.urdf"))
    q, v, a = random_states(model, 8, seed=5)
    recording = model.recording(np.arange(8) / 50.0, q)
    with multiprocessing.get_context("spawn").Pool(2) as pool:
        parts = pool.starmap(model.kinematics, [(q[:4], v[:4], a[:4]), (q[4:], v[4:], a[4:])])
        states = pool.apply(model.states, (recording,))
    whole = model.kinematics(q, v, a)
    for name in whole:
        np.testing.assert_array_equal(np.concatenate([p[name] for p in parts]), whole[name])
    np.testing.assert_array_equal(states["velocity"], model.states(recording)["velocity"])


def test_dask_local_cluster(mbk_kinematics):
    import distributed  # python3-distributed, a test package (scripts/common.sh)
    model = mbk_kinematics.load(source("test/robots/anymal_c.urdf"))
    q, v, a = random_states(model, 16, seed=7)
    recording = model.recording(np.arange(16) / 100.0, q)
    cluster = distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=True,
                                       host="127.0.0.1", dashboard_address=None)
    try:
        with distributed.Client(cluster) as client:
            remote = client.submit(model.kinematics, q, v, a).result()
            recorded = client.submit(model.recording_kinematics, recording).result()
    finally:
        cluster.close()
    local = model.kinematics(q, v, a)
    for name in local:
        np.testing.assert_array_equal(remote[name], local[name], err_msg=name)
    np.testing.assert_array_equal(recorded["velocity"],
                                  model.recording_kinematics(recording)["velocity"])
