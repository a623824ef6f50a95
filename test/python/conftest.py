"""Shared by the Python module's tests (ctest python_module, test/python/python.cmake): where
the sources and the workspace's `mbk` are, and states to evaluate."""
import json
import os
import subprocess

import numpy as np
import pytest

SOURCE = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
# Robots and scenes shipped with the package (config/) and published ones (test/robots/).
MODELS = ["config/human_body.urdf", "config/human_body.yaml", "config/ten_body.yaml",
          "test/robots/panda.urdf", "test/robots/pr2.urdf", "test/robots/baxter.urdf",
          "test/robots/anymal_c.urdf"]


def source(relative):
    return os.path.join(SOURCE, relative)


def mbk_path():
    """The workspace's mbk: MBK_DEVEL (set by ctest) or the devel space on CMAKE_PREFIX_PATH."""
    prefixes = [os.environ.get("MBK_DEVEL", "")] + os.environ.get("CMAKE_PREFIX_PATH", "").split(":")
    for prefix in prefixes:
        path = os.path.join(prefix, "lib", "mb_kinematics", "mbk")
        if prefix and os.path.isfile(path):
            return path
    raise RuntimeError("mbk not found: set MBK_DEVEL to the devel space")


def mbk(*args):
    done = subprocess.run([mbk_path()] + list(args), capture_output=True, text=True)
    if done.returncode:
        raise RuntimeError("mbk %s: %s" % (" ".join(args), done.stderr))
    return done.stdout


def random_states(model, samples, seed):
    """Positions (N, nq), speeds and their derivatives (N, nv): angles in +-1.5 rad, lengths in
    +-0.3 m, Euler parameters of unit norm."""
    rng = np.random.default_rng(seed)
    q = np.tile(model.neutral_position, (samples, 1))
    q += rng.uniform(-1.5, 1.5, q.shape) * 0.2
    for first, name in enumerate(model.coordinate_names):
        if name.endswith("/e1"):
            e = rng.normal(size=(samples, 4))
            q[:, first:first + 4] = e / np.linalg.norm(e, axis=1, keepdims=True)
    return q, rng.uniform(-2, 2, (samples, model.nv)), rng.uniform(-5, 5, (samples, model.nv))


def eval_json(model_path, q, v, a, model, tmp_path, partials=False):
    """`mbk eval` of one state through a STATE.json."""
    mimic = {m["coordinate"] for m in model.mimics}  # set from their sources by both
    q = {n: float(x) for n, x in zip(model.coordinate_names, q) if n not in mimic}
    v = {n: float(x) for n, x in zip(model.speed_names, v) if n not in mimic}
    a = {n: float(x) for n, x in zip(model.speed_names, a) if n not in mimic}
    state = {"position": q, "velocity": v, "acceleration": a}
    path = os.path.join(str(tmp_path), "state.json")
    with open(path, "w") as f:
        json.dump(state, f)  # repr of a float: the shortest text that reads back exactly
    args = ["eval", "--model", model_path, "--state", path]
    return json.loads(mbk(*(args + (["--partial-velocities"] if partials else []))))


@pytest.fixture(scope="session")
def mbk_kinematics():
    import mb_kinematics
    return mb_kinematics
