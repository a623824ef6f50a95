"""Bad input to Model.kinematics: a ValueError or TypeError naming the argument (and for a bad
sample, the sample and the coordinate), never a crash or a silently wrong array; out= arrays
are left untouched."""
import numpy as np
import pytest

from conftest import random_states, source


@pytest.fixture(scope="module")
def human(mbk_kinematics):
    return mbk_kinematics.load(source("config/human_body.urdf"))


def test_shapes(human):
    q, v, a = random_states(human, 4, seed=1)
    with pytest.raises(ValueError, match=r"q: shape \(4, %d\)" % (human.nq - 1)):
        human.kinematics(q[:, 1:])
    with pytest.raises(ValueError, match="q: shape"):
        human.kinematics(q.reshape(2, 2, -1))
    with pytest.raises(ValueError, match="velocity: shape"):
        human.kinematics(q, v[:3])
    with pytest.raises(ValueError, match="acceleration: shape"):
        human.kinematics(q, v, a[:, :2])
    with pytest.raises(ValueError, match="acceleration: given without velocity"):
        human.kinematics(q, acceleration=a)
    with pytest.raises(ValueError, match="velocity: shape"):
        human.kinematics(q[0], v)  # one sample of q, N of velocity


def test_dtypes(human):
    q, _, _ = random_states(human, 2, seed=2)
    with pytest.raises(TypeError, match="q: dtype complex128"):
        human.kinematics(q.astype(complex))
    with pytest.raises(TypeError, match="q: dtype <U"):
        human.kinematics(np.array([["a"] * human.nq]))
    with pytest.raises(TypeError, match="dtype: float64 or float32"):
        human.kinematics(q, dtype=np.int32)
    ints = human.kinematics(np.zeros((1, human.nq), dtype=np.int64))
    assert np.array_equal(ints["origin"], human.kinematics(np.zeros((1, human.nq)))["origin"])
    strided = np.zeros((2, 2 * human.nq))[:, ::2]  # not contiguous: read through a copy
    assert np.array_equal(human.kinematics(strided)["origin"][0], ints["origin"][0])


def test_bad_sample_names_sample_and_coordinate(human):
    q, v, a = random_states(human, 50, seed=3)
    name = human.coordinate_names[5]
    q[37, 5] = np.nan
    v[40, 1] = np.inf
    for threads in (1, 2):
        with pytest.raises(ValueError, match=r"^sample 37: .*'%s': not finite \(nan\)" % name):
            human.kinematics(q, v, a, threads=threads)
    q[37, 5] = 0
    with pytest.raises(ValueError, match="^sample 40: .*speed '%s'" % human.speed_names[1]):
        human.kinematics(q, v, a)
    out = {"origin": np.full((50, human.body_count, 3), 7.0)}
    with pytest.raises(ValueError, match="sample 40"):
        human.kinematics(q, v, out=out)
    assert (out["origin"] == 7.0).all(), "nothing written when a sample is bad"


def test_unknown_names(human):
    q = human.neutral_position
    with pytest.raises(ValueError, match="q: unknown name 'elbow'"):
        human.kinematics({"elbow": 0.1})
    with pytest.raises(ValueError, match="velocity: unknown name"):
        human.kinematics(q, {"nope": 1.0})
    with pytest.raises(ValueError, match="outputs: unknown output 'rotations'"):
        human.kinematics(q, outputs=["rotations"])
    with pytest.raises(ValueError, match="outputs: 'omega' needs velocity"):
        human.kinematics(q, outputs="omega")
    with pytest.raises(ValueError, match="bodies: unknown body 'tail'"):
        human.kinematics(q, bodies=["tail"])
    with pytest.raises(ValueError, match="bodies: index 0 out of range"):
        human.kinematics(q, bodies=[0])
    with pytest.raises(TypeError, match="bodies"):
        human.kinematics(q, bodies=[1.5])
    with pytest.raises(ValueError, match="threads: 0"):
        human.kinematics(q, threads=0)
    with pytest.raises(TypeError, match="threads"):
        human.kinematics(q, threads=1.5)
    with pytest.raises(ValueError, match=r"q\['left_knee'\]: shape"):
        human.kinematics({"right_knee": [0.1, 0.2], "left_knee": [0.1, 0.2, 0.3]})


def test_out_arrays(human):
    q, _, _ = random_states(human, 3, seed=4)
    nb = human.body_count

    def fails(error, pattern, array, **kwargs):
        with pytest.raises(error, match=pattern):
            human.kinematics(q, out={"origin": array}, **kwargs)

    fails(TypeError, r"out\['origin'\]: dtype float32, expected float64",
          np.empty((3, nb, 3), np.float32))
    fails(ValueError, r"out\['origin'\]: shape", np.empty((3, nb + 1, 3)))
    fails(ValueError, "not C-contiguous", np.empty((3, nb, 6))[:, :, ::2])
    read_only = np.empty((3, nb, 3))
    read_only.setflags(write=False)
    fails(ValueError, "read-only", read_only)
    fails(TypeError, "a numpy array", [[0.0] * 3] * nb)
    with pytest.raises(ValueError, match="out: 'omega' is not among"):
        human.kinematics(q, outputs=["origin"], out={"omega": np.empty((3, nb, 3))})
    with pytest.raises(TypeError, match="out: a dict"):
        human.kinematics(q, out=np.empty((3, nb, 3)))
