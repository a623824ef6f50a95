"""Model.kinematics against the peers' Python bindings on the published robots, to 1e-12:
KDL's (PyKDL: poses and chain velocities, the chain built from the URDF as kdl_parser builds
it) and DART's (dartpy: every body's pose, velocities and accelerations, mass centers' too)."""
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from conftest import random_states, source

TOL = 1e-12
ROBOTS = ["test/robots/panda.urdf", "test/robots/pr2.urdf", "test/robots/baxter.urdf"]


def with_mimics(model, q):
    """q with its mimic coordinates set from their sources (as Model.kinematics does)."""
    q = q.copy()
    for m in model.mimics:
        i, s = (model.coordinate_names.index(m[key]) for key in ("coordinate", "source"))
        q[..., i] = m["multiplier"] * q[..., s] + m["offset"]
    return q


def mimic_rates(model, v):
    v = v.copy()
    for m in model.mimics:
        i, s = (model.coordinate_names.index(m[key]) for key in ("coordinate", "source"))
        v[..., i] = m["multiplier"] * v[..., s]
    return v


def urdf_chain(path, tip):
    """The URDF joints from the root link to `tip`: (name, type, xyz, rpy, axis) each."""
    joints = {}
    for j in ET.parse(path).getroot().iter("joint"):
        origin = j.find("origin")
        axis = j.find("axis")
        xyz = [float(x) for x in (origin.get("xyz", "0 0 0") if origin is not None else "0 0 0").split()]
        rpy = [float(x) for x in (origin.get("rpy", "0 0 0") if origin is not None else "0 0 0").split()]
        joints[j.find("child").get("link")] = (
            j.get("name"), j.get("type"), xyz, rpy,
            [float(x) for x in (axis.get("xyz") if axis is not None else "1 0 0").split()],
            j.find("parent").get("link"))
    chain, link = [], tip
    while link in joints:
        chain.append(joints[link])
        link = joints[link][5]
    return chain[::-1]


def kdl_chain(PyKDL, path, tip, mass_center):
    """A KDL chain to the tip's mass center: per URDF joint its origin, then the joint itself
    about its axis (the frame kdl_parser gives each segment), then r_k."""
    chain, names = PyKDL.Chain(), []
    for name, kind, xyz, rpy, axis, _ in urdf_chain(path, tip):
        origin = PyKDL.Frame(PyKDL.Rotation.RPY(*rpy), PyKDL.Vector(*xyz))
        chain.addSegment(PyKDL.Segment(PyKDL.Joint(PyKDL.Joint.Fixed), origin))
        if kind in ("revolute", "continuous", "prismatic"):
            axis_type = PyKDL.Joint.TransAxis if kind == "prismatic" else PyKDL.Joint.RotAxis
            joint = PyKDL.Joint(name, PyKDL.Vector(0, 0, 0), PyKDL.Vector(*axis), axis_type)
            chain.addSegment(PyKDL.Segment(joint, PyKDL.Frame.Identity()))
            names.append(name)
    chain.addSegment(PyKDL.Segment(PyKDL.Joint(PyKDL.Joint.Fixed),
                                   PyKDL.Frame(PyKDL.Vector(*mass_center))))
    return chain, names


TIPS = {"test/robots/panda.urdf": ["panda_hand", "panda_link4"],
        "test/robots/pr2.urdf": ["r_wrist_roll_link", "l_forearm_link", "head_tilt_link"],
        "test/robots/baxter.urdf": ["left_gripper", "right_lower_forearm"]}


@pytest.mark.parametrize("path", ROBOTS)
def test_pykdl_poses_and_chain_velocities(mbk_kinematics, path):
    import PyKDL
    model = mbk_kinematics.load(source(path))
    q, v, _ = random_states(model, 5, seed=11)
    q, v = with_mimics(model, q), mimic_rates(model, v)
    out = model.kinematics(q, v, outputs=["rotation", "mass_center", "omega", "velocity"])
    for tip in TIPS[path]:
        k = model.body_index(tip)
        chain, names = kdl_chain(PyKDL, source(path), tip, model.mass_centers[k - 1])
        columns = [model.coordinate_names.index(n) for n in names]
        solver = PyKDL.ChainFkSolverVel_recursive(chain)
        for s in range(5):
            qq, vv = PyKDL.JntArray(len(names)), PyKDL.JntArray(len(names))
            for i, c in enumerate(columns):
                qq[i], vv[i] = q[s, c], v[s, c]
            frame = PyKDL.FrameVel()
            assert solver.JntToCart(PyKDL.JntArrayVel(qq, vv), frame) >= 0
            pose, twist = frame.GetFrame(), frame.GetTwist()
            rotation = np.array([[pose.M[i, j] for j in range(3)] for i in range(3)])
            np.testing.assert_allclose(out["rotation"][s, k - 1], rotation, rtol=0, atol=TOL)
            np.testing.assert_allclose(out["mass_center"][s, k - 1], list(pose.p), rtol=0, atol=TOL)
            np.testing.assert_allclose(out["omega"][s, k - 1], list(twist.rot), rtol=0, atol=TOL)
            np.testing.assert_allclose(out["velocity"][s, k - 1], list(twist.vel), rtol=0, atol=TOL)


def dart_skeleton(dartpy, path):
    loader = dartpy.utils.DartLoader()
    options = dartpy.utils.DartLoaderOptions()
    options.mDefaultRootJointType = dartpy.utils.DartLoaderRootJointType.FIXED
    loader.setOptions(options)
    return loader.parseSkeleton(path)


@pytest.mark.parametrize("path", ROBOTS)
def test_dartpy_velocities_and_accelerations(mbk_kinematics, path):
    import dartpy
    model = mbk_kinematics.load(source(path))
    skeleton = dart_skeleton(dartpy, source(path))
    q, v, a = random_states(model, 4, seed=12)
    q, v, a = with_mimics(model, q), mimic_rates(model, v), mimic_rates(model, a)
    out = model.kinematics(q, v, a)
    dofs = [model.coordinate_names.index(skeleton.getDof(i).getName())
            for i in range(skeleton.getNumDofs())]
    assert len(dofs) == model.nq
    compared = 0
    for s in range(4):
        skeleton.setPositions(q[s, dofs])
        skeleton.setVelocities(v[s, dofs])
        skeleton.setAccelerations(a[s, dofs])
        for n in range(skeleton.getNumBodyNodes()):
            node = skeleton.getBodyNode(n)
            if node.getName() not in model.body_names:
                continue  # the root link: R
            i = model.body_index(node.getName()) - 1
            where = "%s sample %d %s" % (path, s, node.getName())
            np.testing.assert_allclose(out["rotation"][s, i], node.getTransform().rotation(),
                                       rtol=0, atol=TOL, err_msg=where)
            np.testing.assert_allclose(out["origin"][s, i], node.getTransform().translation(),
                                       rtol=0, atol=TOL, err_msg=where)
            np.testing.assert_allclose(out["mass_center"][s, i], node.getCOM(), rtol=0, atol=TOL,
                                       err_msg=where)
            np.testing.assert_allclose(out["omega"][s, i], node.getAngularVelocity(), rtol=0,
                                       atol=TOL, err_msg=where)
            np.testing.assert_allclose(out["velocity"][s, i], node.getCOMLinearVelocity(),
                                       rtol=0, atol=TOL, err_msg=where)
            np.testing.assert_allclose(out["alpha"][s, i], node.getAngularAcceleration(),
                                       rtol=0, atol=TOL, err_msg=where)
            np.testing.assert_allclose(out["acceleration"][s, i], node.getCOMLinearAcceleration(),
                                       rtol=0, atol=TOL, err_msg=where)
            compared += 1
    assert compared == 4 * model.body_count
