"""A model library that cannot be loaded at run time (libmujoco for MJCF, libsdformat12 under the
SDFormat reader, both opened with dlopen when a model first needs them): `mbk` prints one error
line naming the library and the Debian package that installs it, exit status 1, and
mb_kinematics.load() raises with the same line. The library is made unloadable the way a
damaged or missing install makes it: an empty file of its name first on LD_LIBRARY_PATH, which
the dynamic loader opens instead of the system's and refuses ("file too short")."""
import os
import shutil
import subprocess
import sys

import pytest

from conftest import mbk_path, source

LIBRARIES = [  # (model, the library's file name, its Debian package)
    ("test/robots/mjcf/panda.xml", "libmujoco.so.2.2.2", "libmujoco2.2.2"),
    ("test/robots/sdf/double_pendulum.sdf", "libsdformat12.so.12", "libsdformat12-12"),
]

LOAD = """import sys, mb_kinematics
try:
    mb_kinematics.load(sys.argv[1])
except Exception as e:
    print("%s: %s" % (type(e).__name__, e))
"""


def installing_package(library):
    """The Debian package that installed `library` on this machine (dpkg -S), else None."""
    if not shutil.which("dpkg"):
        return None
    found = subprocess.run(["dpkg", "-S", "/" + library], capture_output=True, text=True)
    return found.stdout.split(":", 1)[0] if found.returncode == 0 else None


@pytest.mark.parametrize("model, library, package", LIBRARIES)
def test_an_unloadable_model_library_is_one_line_naming_its_package(tmp_path, model, library,
                                                                    package):
    assert installing_package(library) in (None, package)  # the package named is the right one
    broken, run = tmp_path / "lib", tmp_path / "run"  # run: no library (LD_LIBRARY_PATH may name
    broken.mkdir(), run.mkdir()                     # the working folder with an empty entry)
    (broken / library).write_bytes(b"")
    env = dict(os.environ, LD_LIBRARY_PATH="%s:%s" % (broken, os.environ.get("LD_LIBRARY_PATH",
                                                                               "")))
    done = subprocess.run([mbk_path(), "tables", "--model", source(model)], env=env, cwd=run,
                          capture_output=True, text=True)
    line = "%s (Debian package %s, which " % (library, package)
    assert (done.returncode, done.stdout) == (1, ""), done.stderr
    assert done.stderr.startswith("mbk: error: ") and done.stderr.count("\n") == 1, done.stderr
    assert line in done.stderr and str(broken / library) in done.stderr, done.stderr
    loaded = subprocess.run([sys.executable, "-c", LOAD, source(model)], env=env, cwd=run,
                            capture_output=True, text=True)
    assert loaded.stdout == "RuntimeError: " + done.stderr[len("mbk: error: "):], loaded.stderr
    alone = subprocess.run([mbk_path(), "tables", "--model", source(model)], cwd=run,
                           capture_output=True, text=True)
    assert alone.returncode == 0, alone.stderr  # the installed library loads
