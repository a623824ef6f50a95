"""mb_kinematics.load and the model's introspection: URDF files and texts, YAML scenes, BVH
(scale, body mass), warnings, the loaders' errors as ValueError; names, masses, mass centers,
lower body arrays and their table as `mbk tables` prints it, mimics, joint types."""
import numpy as np
import pytest

from conftest import mbk, source


def test_urdf_file_and_text_give_the_same_model(mbk_kinematics):
    path = source("test/robots/panda.urdf")
    from_file = mbk_kinematics.load(path)
    with open(path) as f:
        from_text = mbk_kinematics.load(f.read())  # as rospy.get_param("robot_description")
    assert from_file.body_names == from_text.body_names
    assert from_file.coordinate_names == from_text.coordinate_names
    q = np.linspace(-1, 1, from_file.nq)
    assert np.array_equal(from_file.kinematics(q)["rotation"], from_text.kinematics(q)["rotation"])
    assert from_file.joint_types.count("revolute") == 7  # the arm; fingers prismatic
    assert "prismatic" in from_file.joint_types


def test_mjcf_file_and_text_give_the_same_model(mbk_kinematics):
    path = source("test/robots/mjcf/panda.xml")  # MuJoCo compiles it (doc/conventions.md)
    from_file = mbk_kinematics.load(path)
    with open(path) as f:
        from_text = mbk_kinematics.load(f.read())
    assert from_file.body_names == from_text.body_names
    assert "link7" in from_file.body_names and "hand" in from_file.body_names
    assert from_file.coordinate_names == from_text.coordinate_names
    assert "finger_joint1" in from_file.coordinate_names
    q = np.linspace(-1, 1, from_file.nq)
    assert np.array_equal(from_file.kinematics(q)["rotation"], from_text.kinematics(q)["rotation"])
    with pytest.raises(ValueError, match="<text>: MuJoCo refuses the model: XML parse error"):
        mbk_kinematics.load("<mujoco><worldbod\n")


def test_introspection_against_mbk_tables(mbk_kinematics):
    path = source("config/ten_body.yaml")
    model = mbk_kinematics.load(path)
    assert list(model.lower) == [0, 1, 2, 1, 1, 5, 2, 7, 8, 9]  # the chapter's Fig. 4.2.1
    assert model.tables() == mbk("tables", "--model", path)
    csv = [[int(x) for x in line.split(",")] for line in
           mbk("tables", "--model", path, "--csv").split()]
    assert np.array_equal(model.lower_table, np.array(csv))
    assert model.body_names[0] == "B1" and model.joint_names[9] == "J10"
    assert model.masses[1] == 3.0 and list(model.mass_centers[3]) == [0.15, 0, 0]
    assert model.coordinate_names[:3] == ("J1/alpha", "J1/beta", "J1/gamma")
    assert model.speed_names == model.coordinate_names and model.nq == model.nv == 30
    assert set(model.joint_types) == {"ball_123"}
    assert model.body_index("B7") == 7
    with pytest.raises(ValueError, match="'B11'"):
        model.body_index("B11")
    with pytest.raises(ValueError):
        model.masses[0] = 1  # read-only: the model is immutable


def test_yaml_text_and_euler_speeds(mbk_kinematics):
    with open(source("config/human_body.yaml")) as f:
        model = mbk_kinematics.load(f.read())
    assert model.body_count == mbk_kinematics.load(source("config/human_body.yaml")).body_count


def test_mimics(mbk_kinematics):
    model = mbk_kinematics.load(source("test/robots/pr2.urdf"))
    m = {x["coordinate"]: x for x in model.mimics}
    assert m["r_gripper_r_finger_joint"]["source"] == "r_gripper_l_finger_joint"
    assert m["r_gripper_r_finger_joint"]["multiplier"] == 1.0


def test_bvh_options_and_warnings(mbk_kinematics):
    path = source("test/mocap/131_01.bvh")
    plain = mbk_kinematics.load(path)
    assert plain.masses.sum() == 0  # no body mass: massless segments
    assert any("scale" in w for w in plain.warnings)  # inches read as metres: a giant
    scaled = mbk_kinematics.load(path, scale=0.056444, body_mass=68.5, sex="male")
    assert scaled.masses.sum() == pytest.approx(68.5)
    assert not any("scale" in w for w in scaled.warnings)
    assert scaled.coordinate_names == plain.coordinate_names


def test_errors_are_the_loaders_messages(mbk_kinematics, tmp_path):
    missing = str(tmp_path / "none.urdf")
    with pytest.raises(ValueError, match="none.urdf"):
        mbk_kinematics.load(missing)
    with pytest.raises(ValueError, match="unknown model file type"):
        mbk_kinematics.load(str(tmp_path / "robot.stl"))
    with pytest.raises(ValueError, match="bvh"):
        mbk_kinematics.load(source("test/robots/panda.urdf"), scale=0.01)
    with pytest.raises(ValueError, match="^<text>:1: URDF does not parse"):
        mbk_kinematics.load("<robot name='r'><link name='a'/>")
    with pytest.raises(ValueError, match="<text>:2"):
        mbk_kinematics.load("bodies:\n  - {name: a, lower: 3}\n")
    with pytest.raises(ValueError, match="sex"):
        mbk_kinematics.load(source("test/mocap/131_01.bvh"), sex="other")
    with pytest.raises(TypeError, match="path_or_text"):
        mbk_kinematics.load(42)
    with pytest.raises(TypeError, match="scale"):
        mbk_kinematics.load(source("test/mocap/131_01.bvh"), scale="0.05")
    with pytest.raises(TypeError):
        mbk_kinematics.load(source("test/mocap/131_01.bvh"), scael=0.05)
    one_line = None
    try:
        mbk_kinematics.load("<robot name='r'><link name='a'/>")
    except ValueError as e:
        one_line = str(e)
    assert one_line and "\n" not in one_line


def test_a_long_chain_loads_without_its_lower_body_table(tmp_path):
    """The table has a row per level: N^2 entries on a chain of N bodies,
    so load() must not make it (it took 0.9 GB here at N = 5,000, 14 GB at N = 20,000); a child
    process, so that its peak memory is its own."""
    import subprocess
    import sys
    scene = tmp_path / "chain.yaml"
    scene.write_text("{lower_body_array: [" + ", ".join(str(k) for k in range(5000)) + "]}\n")
    script = ("import resource, mb_kinematics as m; before = resource.getrusage("
              "resource.RUSAGE_SELF).ru_maxrss; model = m.load(%r); assert model.body_count == "
              "5000; print(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before)"
              % str(scene))
    grown_kb = int(subprocess.run([sys.executable, "-c", script], check=True,
                                  capture_output=True, text=True, timeout=120).stdout)
    assert grown_kb < 100 * 1024  # 18 MB: the model and its Python lists


def test_bvh_segments_map(mbk_kinematics, tmp_path):
    """load(..., segments=MAP): the map gives the segments as mbk's --segments; a map naming
    the joints the rules find changes nothing; without body_mass it is refused."""
    bvh = source("test/mocap/131_01.bvh")
    rules = mbk_kinematics.load(bvh, scale=0.056444, body_mass=68.5)
    path = tmp_path / "map.yaml"
    path.write_text("LeftAnkle: left_foot\nhead: {joint: Head, distal: lowerneck}\n")
    mapped = mbk_kinematics.load(bvh, scale=0.056444, body_mass=68.5, segments=path)
    assert np.array_equal(mapped.masses, rules.masses)
    assert np.allclose(mapped.mass_centers, rules.mass_centers, rtol=0, atol=1e-15)
    path.write_text("LeftWrist: left_foot\n")  # the hand carries the foot's mass now
    moved = mbk_kinematics.load(bvh, scale=0.056444, body_mass=68.5, segments=str(path))
    assert moved.masses[moved.body_index("LeftWrist") - 1] > rules.masses[
        rules.body_index("LeftWrist") - 1]
    with pytest.raises(ValueError, match="segments maps joints to masses: it needs body_mass"):
        mbk_kinematics.load(bvh, scale=0.056444, segments=str(path))
    with pytest.raises(TypeError, match="segments: a file name"):
        mbk_kinematics.load(bvh, body_mass=68.5, segments=3)
