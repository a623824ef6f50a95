"""Typing and introspection (doc/python.md): the version, the public names, the stubs shipped
beside the package and true to it (mypy's stubtest), read-only attributes, the Recording's
docstrings and repr, FileNotFoundError for a missing file."""
import ast
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from conftest import source

BVH = source("test/mocap/131_01.bvh")


def test_version_is_package_xml_s(mbk_kinematics):
    version = ET.parse(source("package.xml")).getroot().findtext("version")
    assert mbk_kinematics.__version__ == version


def test_dir_lists_the_public_names_only(mbk_kinematics):
    names = dir(mbk_kinematics)
    assert set(mbk_kinematics.__all__) <= set(names)
    assert not {"np", "os", "operator", "pkgutil", "errno", "hashlib", "_core"} & set(names)
    for name in mbk_kinematics.__all__:
        assert getattr(mbk_kinematics, name) is not None, name


def package_folder(mbk_kinematics):
    return os.path.dirname(mbk_kinematics._core.__file__)  # the devel (or install) space's


def test_stubs_and_marker_are_shipped_beside_the_package(mbk_kinematics):
    folder = package_folder(mbk_kinematics)
    assert os.path.isfile(os.path.join(folder, "py.typed"))
    with open(os.path.join(folder, "__init__.pyi")) as f:
        stub = ast.parse(f.read())
    defined = {n.name for n in stub.body if isinstance(n, (ast.FunctionDef, ast.ClassDef))}
    defined |= {t.id for n in stub.body if isinstance(n, ast.AnnAssign) for t in [n.target]}
    assert set(mbk_kinematics.__all__) <= defined
    for cls in ("Model", "Recording"):
        node = next(n for n in stub.body if isinstance(n, ast.ClassDef) and n.name == cls)
        in_stub = {n.name for n in node.body if isinstance(n, ast.FunctionDef)}
        runtime = getattr(mbk_kinematics, cls)
        public = {n for n in vars(runtime) if not n.startswith("_")}
        assert public <= in_stub, (cls, public - in_stub)


def test_stubtest_finds_the_stubs_true(mbk_kinematics, tmp_path):
    """mypy's stubtest imports the package and compares every stub with the runtime object."""
    env = dict(os.environ, MYPYPATH=package_folder(mbk_kinematics), MYPY_CACHE_DIR=str(tmp_path))
    # --ignore-missing-stub: the private modules (_core, the compiled part) have no stubs.
    done = subprocess.run([sys.executable, "-m", "mypy.stubtest", "mb_kinematics",
                           "--ignore-missing-stub"],
                          capture_output=True, text=True, env=env, cwd=str(tmp_path))
    assert done.returncode == 0, done.stdout + done.stderr


@pytest.mark.parametrize("name", ["nq", "nv", "frame", "body_names", "coordinate_names",
                                  "speed_names", "joint_names", "joint_types", "masses",
                                  "mass_centers", "lower", "mimics", "warnings",
                                  "neutral_position", "body_count", "root", "lower_table"])
def test_model_attributes_are_read_only(mbk_kinematics, name):
    model = mbk_kinematics.load(source("config/ten_body.yaml"))
    before = getattr(model, name)
    with pytest.raises(AttributeError):
        setattr(model, name, 3)
    with pytest.raises(AttributeError):
        delattr(model, name)
    after = getattr(model, name)
    assert type(after) is type(before)
    if isinstance(before, np.ndarray):
        assert not after.flags.writeable
        np.testing.assert_array_equal(after, before)
    else:
        assert after == before
    with pytest.raises(AttributeError):
        model.new_attribute = 1


def test_recording_has_docstrings_and_a_readable_repr(mbk_kinematics):
    recording_type = mbk_kinematics.Recording
    assert recording_type.__doc__ and "read_recording" in recording_type.__doc__
    for name in ("times", "positions", "velocities", "accelerations", "grid", "drops", "base"):
        doc = getattr(recording_type, name).__doc__
        assert doc and len(doc) > 20, name
    model = mbk_kinematics.load(BVH, scale=0.056444)
    recording = model.read_recording(BVH, scale=0.056444)
    assert len(recording) == len(recording.times)
    text = repr(recording)
    assert text == ("<mb_kinematics.Recording: %d rows x %d coordinates, %.6g-%.6g s, 120 Hz grid>"
                    % (len(recording), model.nq, recording.times[0], recording.times[-1])), text
    with pytest.raises(AttributeError):
        recording.times = np.zeros(3)


def test_missing_files_raise_file_not_found(mbk_kinematics, tmp_path):
    missing = str(tmp_path / "robot.urdf")
    with pytest.raises(FileNotFoundError) as e:
        mbk_kinematics.load(missing)
    assert e.value.filename == missing and missing in str(e.value)  # the loader's message
    assert isinstance(e.value, ValueError)  # as every other loader error
    model = mbk_kinematics.load(source("config/ten_body.yaml"))
    with pytest.raises(FileNotFoundError) as e:
        model.read_recording(str(tmp_path / "run.bag"))
    assert e.value.filename == str(tmp_path / "run.bag")
    with pytest.raises(ValueError, match="unknown model file type"):  # present, but not a model
        mbk_kinematics.load(source("README.md"))
