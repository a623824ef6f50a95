"""The worked examples of doc/python.md run as they stand (each ```python block in a directory of
its own) and write their figures."""
import os
import re
import subprocess
import sys

import pytest

from conftest import source

BLOCKS = re.findall(r"^```python\n(.*?)^```", open(source("doc/python.md")).read(), re.S | re.M)


@pytest.mark.parametrize("block", range(len(BLOCKS)))
def test_example_runs(block, tmp_path):
    env = dict(os.environ, ROS_PACKAGE_PATH=source(""), MPLBACKEND="Agg")
    done = subprocess.run([sys.executable, "-c", BLOCKS[block]], cwd=str(tmp_path), env=env,
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert list(tmp_path.glob("*.png")), "no figure written"


def test_every_example_found():
    assert len(BLOCKS) == 3
