"""Fresh arrays above 1 MiB in blocks the module keeps when they are released
(offline/retained_blocks.h): a block goes to a new array only once no array (or view) of the
old one is left, a smaller array (a chunk's) takes part of a larger released one, the numbers are
those written into arrays of the caller's own, and release_memory() hands the kept blocks
back."""
import gc
import mmap

import numpy as np
import pytest

from conftest import source

SAMPLES = 2000  # rotation: 2000 x 37 x 72 bytes, 5.3 MB


@pytest.fixture(scope="module")
def human(mbk_kinematics):
    model = mbk_kinematics.load(source("config/human_body.urdf"))
    rng = np.random.default_rng(4)
    states = [rng.uniform(-0.5, 0.5, (SAMPLES, n)) for n in (model.nq, model.nv, model.nv)]
    return model, states


def reference(model, states):
    """The same call into arrays made here (np.zeros: never from the module's blocks)."""
    shapes = {k: a.shape for k, a in model.kinematics(*(x[:1] for x in states)).items()}
    out = {k: np.zeros((SAMPLES,) + s[1:]) for k, s in shapes.items()}
    model.kinematics(*states, out=out, threads=2)
    return out


def address(a):
    return a.__array_interface__["data"][0]


def blocks(arrays):
    """The memory of the arrays above 1 MiB (the module's blocks: whole pages), as (start, end)
    ranges, those that touch joined."""
    spans = sorted((address(a), address(a) + -(-a.nbytes // mmap.PAGESIZE) * mmap.PAGESIZE)
                   for a in arrays.values() if a.nbytes > 1 << 20)
    joined = spans[:1]
    for begin, end in spans[1:]:
        if begin == joined[-1][1]:
            joined[-1] = (joined[-1][0], end)
        else:
            joined.append((begin, end))
    return joined


def inside(a, ranges):
    return any(begin <= address(a) and address(a) + a.nbytes <= end for begin, end in ranges)


def test_released_arrays_memory_is_reused(mbk_kinematics, human):
    model, states = human
    expected = reference(model, states)
    mbk_kinematics.release_memory()  # no block of another test's in the way
    first = model.kinematics(*states, threads=2)
    released = blocks(first)
    del first
    gc.collect()
    kept = mbk_kinematics._core.kept_bytes()
    assert kept == sum(end - begin for begin, end in released)
    second = model.kinematics(*states, threads=2)
    assert mbk_kinematics._core.kept_bytes() == 0  # every block from the memory released
    for name, a in second.items():
        assert a.nbytes <= 1 << 20 or inside(a, released), name
    for name, a in expected.items():
        assert np.array_equal(second[name], a, equal_nan=True), name
        assert second[name].flags.writeable and second[name].flags.c_contiguous, name


def test_chunks_take_the_blocks_a_larger_call_released(mbk_kinematics, human):
    """kinematics_chunks after a call of all the samples: the first chunk's arrays above 1 MiB
    are made in the blocks that call's arrays released (no new memory from the kernel), and
    handed back to them after the loop."""
    model, states = human
    expected = reference(model, states)
    mbk_kinematics.release_memory()
    whole = model.kinematics(*states, threads=2)
    released = blocks(whole)
    del whole
    gc.collect()
    kept = mbk_kinematics._core.kept_bytes()
    rows = SAMPLES // 2  # rotation: 2.7 MB per chunk, the other outputs below 1 MiB
    for start, out in model.kinematics_chunks(*states, rows=rows, threads=2):
        if start == 0:
            chunk = blocks(out)
            assert len(chunk) == 1 and inside(out["rotation"], released)
            assert mbk_kinematics._core.kept_bytes() == kept - (chunk[0][1] - chunk[0][0])
        for name, a in out.items():
            assert np.array_equal(a, expected[name][start:start + rows], equal_nan=True), name
    del out
    gc.collect()
    assert mbk_kinematics._core.kept_bytes() == kept


def test_arrays_still_referenced_are_never_handed_out(human):
    model, states = human
    held = model.kinematics(*states, threads=2)
    view = held["origin"][5:]  # a view keeps its array's block
    rotation = held["rotation"]
    del held
    gc.collect()
    kept = {"rotation": rotation.copy(), "origin": view.copy()}
    shifted = [x[::-1].copy() for x in states]  # other numbers, written over any shared memory
    fresh = model.kinematics(*shifted, threads=2)
    for a in fresh.values():
        assert not np.shares_memory(a, rotation) and not np.shares_memory(a, view)
    assert np.array_equal(rotation, kept["rotation"])
    assert np.array_equal(view, kept["origin"])


def test_release_memory_returns_the_kept_blocks(mbk_kinematics, human):
    model, states = human
    out = model.kinematics(*states, threads=2)
    total = sum(a.nbytes for a in out.values() if a.nbytes > 1 << 20)
    del out
    gc.collect()
    kept = mbk_kinematics._core.kept_bytes()
    assert kept >= total
    assert mbk_kinematics.release_memory() == kept
    assert mbk_kinematics._core.kept_bytes() == 0
    expected = reference(model, states)
    again = model.kinematics(*states, threads=2)
    for name, a in expected.items():
        assert np.array_equal(again[name], a, equal_nan=True), name


def test_float32_arrays(human):
    model, states = human
    out = model.kinematics(*states, threads=2, dtype=np.float32)
    single = {k: np.zeros(a.shape, np.float32) for k, a in out.items()}
    model.kinematics(*states, threads=2, dtype=np.float32, out=single)
    for name, a in single.items():
        assert out[name].dtype == np.float32
        assert np.array_equal(out[name], a, equal_nan=True), name
