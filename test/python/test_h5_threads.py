"""mbk bag --h5 on a recording longer than one of the streamed path's chunks (offline/offline_stream.h,
8192 rows): real motion (test/mocap/131_01.bvh played forwards, backwards and forwards again),
whose rows are computed chunk by chunk and block by block on the computing threads while the
main thread writes. Every thread count gives the same file, byte for byte, with every frame once,
in order: the time grows by the frame time, and a frame played backwards has the same positions
as the frame played forwards. With the rows kept in memory between the passes (9000 frames) and
read again for each pass (10400 frames, past mbk bag's bound on the rows kept)."""
import os

import numpy as np
import pytest

from conftest import source
from test_h5_output import run_bag

h5py = pytest.importorskip("h5py")  # python3-h5py: a test dependency (scripts/common.sh)

BVH = source("test/mocap/131_01.bvh")
SCALE = "0.056444"


def back_and_forth(tmp_path, frames):
    """131_01.bvh's motion played forwards, backwards and so on (each turn's end frame once), to
    `frames` frames; with, for each frame, the index of the recorded frame it plays."""
    with open(BVH) as f:
        lines = f.read().split("\n")
    motion = lines.index("MOTION")
    recorded = [line for line in lines[motion + 3:] if line.strip()]
    n = len(recorded)
    cycle = list(range(n)) + list(range(n - 2, 0, -1))
    played = [cycle[i % len(cycle)] for i in range(frames)]
    lines[motion + 1] = "Frames: %d" % frames
    path = str(tmp_path / ("walk_%d.bvh" % frames))
    with open(path, "w") as f:
        f.write("\n".join(lines[:motion + 3] + [recorded[i] for i in played]) + "\n")
    frame_time = float(lines[motion + 2].split(":")[1])
    return path, np.array(played), frame_time


@pytest.mark.parametrize("frames,threads", [(9000, ["1", "2", "3"]), (10400, ["1", "2"])])
def test_h5_the_same_on_any_thread_count_every_frame_once_in_order(tmp_path, frames, threads):
    bvh, played, frame_time = back_and_forth(tmp_path, frames)
    files = []
    for count in threads:
        path = str(tmp_path / ("threads_%s.h5" % count))
        status, err = run_bag(bvh, "--scale", SCALE, "--h5", path, "--threads", count)
        assert status == 0, err
        files.append(path)
    with open(files[0], "rb") as f:
        first = f.read()
    for path in files[1:]:
        with open(path, "rb") as f:
            assert f.read() == first, path + " differs from one thread's file"
    with h5py.File(files[0], "r") as h5:
        time, origin, rotation = h5["time"][...], h5["origin"][...], h5["rotation"][...]
    assert len(time) == frames  # auto estimates up to the ends: every frame is written
    np.testing.assert_allclose(np.diff(time), frame_time, rtol=1e-6)
    # A frame and its replay (backwards or in a later turn) have the same joint positions: the
    # same poses, bit for bit, in the rows of the frames that play them.
    first_row = {}
    for i, frame in enumerate(played):
        j = first_row.setdefault(frame, i)
        assert np.array_equal(origin[i], origin[j]) and np.array_equal(rotation[i], rotation[j]), i
