"""Model.kinematics_chunks: the results of one call, chunk by chunk, in the memory of one chunk
(tracemalloc counts numpy's arrays), or into the caller's arrays (out=); a chunk size of 0 or
less is a ValueError naming `rows`, out= arrays of another length one naming the array. And one large call on two threads equals the same samples computed in small calls on one, in
float64 and float32."""
import tracemalloc

import numpy as np
import pytest

from conftest import random_states, source


@pytest.fixture(scope="module")
def human(mbk_kinematics):
    return mbk_kinematics.load(source("config/human_body.urdf"))


def test_chunks_are_the_one_call_in_fixed_memory(human):
    q, v, a = random_states(human, 2500, seed=5)
    whole = human.kinematics(q, v, a, threads=2)
    starts = []
    for start, out in human.kinematics_chunks(q, v, a, rows=300, threads=2):
        starts.append(start)
        size = len(out["rotation"])
        assert size == min(300, 2500 - start)
        for name, array in out.items():
            assert np.array_equal(array, whole[name][start:start + size], equal_nan=True)
    assert starts == list(range(0, 2500, 300))
    tracemalloc.start()
    try:
        for start, out in human.kinematics_chunks(q, v, a, rows=300, threads=2):
            pass
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    chunk_bytes = sum(x[:300].nbytes for x in whole.values())
    assert chunk_bytes < peak < 1.2 * chunk_bytes  # one chunk's arrays, not 2500 samples'
    only = list(human.kinematics_chunks(q[:10], v[:10], outputs=["omega"], rows=4))
    assert [s for s, _ in only] == [0, 4, 8] and set(only[0][1]) == {"omega"}


def test_bad_chunk_sizes(human):
    q = np.zeros((5, human.nq))
    for rows in (0, -3):
        with pytest.raises(ValueError, match="rows: %d, expected at least 1" % rows):
            next(human.kinematics_chunks(q, rows=rows))
    with pytest.raises(TypeError, match="rows: an integer"):
        next(human.kinematics_chunks(q, rows=2.5))
    for out in ({"rotation": np.zeros((3, human.body_count, 3, 3))}, {"rotation": 1.0}):
        with pytest.raises(ValueError, match=r"out\['rotation'\]: .*expected 2 rows \(rows=2\)"):
            next(human.kinematics_chunks(q, rows=2, out=out))
    with pytest.raises(TypeError, match="out: a dict"):
        next(human.kinematics_chunks(q, rows=2, out=[]))


def test_chunks_into_arrays_of_ones_own(human):
    """out=: every chunk written into the caller's arrays of `rows` rows (a view of their first
    rows yielded), the outputs not in it allocated once, the same numbers as one call."""
    q, v, a = random_states(human, 1000, seed=7)
    whole = human.kinematics(q, v, a, outputs=["omega", "origin"], threads=2)
    mine = {"omega": np.full((300, human.body_count, 3), np.nan)}
    seen = set()
    for start, out in human.kinematics_chunks(q, v, a, rows=300, out=mine,
                                              outputs=["omega", "origin"], threads=2):
        size = min(300, 1000 - start)
        assert np.shares_memory(out["omega"], mine["omega"])
        seen.add(out["origin"].__array_interface__["data"][0])
        for name in ("omega", "origin"):
            assert np.array_equal(out[name], whole[name][start:start + size])
    assert np.array_equal(mine["omega"][:100], whole["omega"][900:])  # the last chunk's
    assert len(seen) == 1  # origin's array allocated once, reused


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_one_call_equals_small_calls(human, dtype):
    """6000 samples of the default outputs (48 MB in float64, 24 in float32) in one call, streamed
    (above 16 MiB), and in calls of 20 samples, written in place."""
    q, v, a = random_states(human, 6000, seed=6)
    big = human.kinematics(q, v, a, outputs=None, threads=2, dtype=dtype)
    for start in range(0, 6000, 20):
        small = human.kinematics(q[start:start + 20], v[start:start + 20], a[start:start + 20],
                                 threads=1, dtype=dtype)
        for name in small:
            assert np.array_equal(small[name], big[name][start:start + 20], equal_nan=True), name
