"""Model.kinematics: `mbk eval`'s numbers bit for bit on the shipped models, on any number of
threads; the outputs' names, shapes, levels and dtypes; chosen bodies; dict inputs; out=."""
import numpy as np
import pytest

from conftest import MODELS, eval_json, random_states, source

BODY_FIELDS = ["rotation", "origin", "mass_center", "omega", "alpha", "velocity", "acceleration"]
SYSTEM_FIELDS = {"system_mass": "mass", "system_mass_center": "mass_center",
                 "system_velocity": "velocity", "system_acceleration": "acceleration",
                 "linear_momentum": "linear_momentum", "angular_momentum": "angular_momentum"}
PARTIALS = ["partial_omega", "partial_velocity", "partial_omega_dot", "partial_velocity_dot"]


def same_numbers(expected, actual, where):
    """Equal as numbers: 0 ulp (`mbk eval`'s JSON writes -0 as 0, the one difference allowed)."""
    expected = np.asarray(expected, dtype=np.float64).reshape(actual.shape)  # eval: row-major
    assert np.array_equal(expected, actual), "%s: %s vs %s" % (where, expected, actual)


def same_bits(expected, actual, where):
    expected = np.asarray(expected, dtype=np.float64)
    assert expected.shape == actual.shape, where
    assert np.array_equal(expected.view(np.uint64), actual.view(np.uint64)), (
        "%s: %s vs %s" % (where, expected, actual))


@pytest.mark.parametrize("path", MODELS)
def test_every_sample_is_mbk_eval_bit_for_bit(mbk_kinematics, path, tmp_path):
    model = mbk_kinematics.load(source(path))
    q, v, a = random_states(model, 3, seed=len(path))
    out = model.kinematics(q, v, a, outputs=list(mbk_kinematics.OUTPUTS), threads=2)
    for s in range(3):
        expected = eval_json(source(path), q[s], v[s], a[s], model, tmp_path, partials=True)
        for i, body in enumerate(expected["bodies"]):
            assert body["name"] == model.body_names[i]
            for field in BODY_FIELDS:
                same_numbers(body[field], out[field][s, i], "%s sample %d body %s %s" %
                          (path, s, body["name"], field))
            for field in PARTIALS:
                dense = np.zeros((model.nv, 3))
                for name, column in body[field].items():
                    dense[model.speed_names.index(name)] = column
                same_numbers(dense, out[field][s, i], "%s %s %s" % (path, body["name"], field))
        system = expected["system"]
        for field, key in SYSTEM_FIELDS.items():
            value = system[key]
            if value is None:  # eval's null: no inertia for the angular momentum
                assert np.isnan(out[field][s]).all(), field
            else:
                same_numbers(value, out[field][s], "%s sample %d system %s" % (path, s, field))


def test_threads_give_the_same_bits(mbk_kinematics):
    model = mbk_kinematics.load(source("test/robots/pr2.urdf"))
    q, v, a = random_states(model, 101, seed=3)
    outputs = list(mbk_kinematics.OUTPUTS)
    one = model.kinematics(q, v, a, outputs=outputs, threads=1)
    for threads in (2, 3, 7, None):
        many = model.kinematics(q, v, a, outputs=outputs, threads=threads)
        for name in outputs:
            same_bits(one[name], many[name], "%s with %s threads" % (name, threads))


def test_shapes_and_default_outputs(mbk_kinematics):
    model = mbk_kinematics.load(source("config/human_body.urdf"))
    nb = model.body_count
    q, v, a = random_states(model, 5, seed=1)
    pose = model.kinematics(q)
    assert sorted(pose) == sorted(["rotation", "origin", "mass_center", "system_mass",
                                   "system_mass_center"])
    assert pose["rotation"].shape == (5, nb, 3, 3)
    assert pose["origin"].shape == (5, nb, 3)
    assert pose["system_mass"].shape == (5,)
    velocity = model.kinematics(q, v)
    assert "omega" in velocity and "alpha" not in velocity and "angular_momentum" in velocity
    full = model.kinematics(q, v, a)
    assert set(full) == set(BODY_FIELDS) | set(SYSTEM_FIELDS)
    assert not set(PARTIALS) & set(full)
    for name in pose:
        same_bits(full[name], pose[name], name + ": a pose-only call's numbers")
    partial = model.kinematics(q, v, a, outputs="partial_velocity", bodies=["head"])
    assert list(partial) == ["partial_velocity"]
    assert partial["partial_velocity"].shape == (5, 1, model.nv, 3)
    one = model.kinematics(q[2], v[2], a[2])
    for name in full:
        same_bits(full[name][2], one[name], name + ": a (nq,) q drops the N axis")


def test_chosen_bodies_in_their_order(mbk_kinematics):
    model = mbk_kinematics.load(source("test/robots/panda.urdf"))
    q, v, a = random_states(model, 4, seed=2)
    full = model.kinematics(q, v, a)
    names = [model.body_names[-1], model.body_names[0], model.body_names[-1]]
    chosen = model.kinematics(q, v, a, bodies=names)
    by_index = model.kinematics(q, v, a, bodies=[model.body_index(n) for n in names])
    for name in BODY_FIELDS:
        same_bits(full[name][:, [model.body_count - 1, 0, model.body_count - 1]], chosen[name], name)
        same_bits(chosen[name], by_index[name], name)


def test_float32_is_the_float64_rounded(mbk_kinematics):
    model = mbk_kinematics.load(source("config/human_body.yaml"))
    q, v, a = random_states(model, 6, seed=4)
    d = model.kinematics(q, v, a)
    f = model.kinematics(q, v, a, dtype=np.float32)
    for name in d:
        assert f[name].dtype == np.float32
        assert np.array_equal(d[name].astype(np.float32), f[name], equal_nan=True), name


def test_dict_input_as_joint_states_name_them(mbk_kinematics):
    model = mbk_kinematics.load(source("test/robots/pr2.urdf"))
    assert model.mimics, "pr2.urdf's gripper mimics"
    q, v, a = random_states(model, 3, seed=5)
    mimic = {m["coordinate"] for m in model.mimics}
    names = [n for n in model.coordinate_names if n not in mimic]
    columns = [model.coordinate_names.index(n) for n in names]
    as_dict = model.kinematics({n: q[:, c] for n, c in zip(names, columns)},
                               {n: v[:, c] for n, c in zip(names, columns)},
                               {n: a[:, c] for n, c in zip(names, columns)})
    as_array = model.kinematics(q, v, a)  # its mimic columns overwritten from their sources
    for name in as_array:
        same_bits(as_array[name], as_dict[name], name)
    m = model.mimics[0]
    wrong = q.copy()
    wrong[:, model.coordinate_names.index(m["coordinate"])] += 0.3
    same_bits(as_array["rotation"], model.kinematics(wrong, v, a)["rotation"],
              "a mimic coordinate's column is set from its source")
    single = model.kinematics({names[0]: 0.25})
    q0 = model.neutral_position.copy()
    q0[columns[0]] = 0.25
    same_bits(model.kinematics(q0)["origin"], single["origin"], "missing names: the neutral state")


def test_out_arrays_written_in_place(mbk_kinematics):
    model = mbk_kinematics.load(source("config/human_body.urdf"))
    q, v, a = random_states(model, 8, seed=6)
    expected = model.kinematics(q, v, a, outputs=["rotation", "acceleration"])
    out = {"rotation": np.full((8, model.body_count, 3, 3), np.nan),
           "acceleration": np.empty((8, model.body_count, 3))}
    result = model.kinematics(q, v, a, out=out)
    assert result["rotation"] is out["rotation"] or np.shares_memory(result["rotation"],
                                                                     out["rotation"])
    for name in out:
        same_bits(expected[name], out[name], name)
    single = {"origin": np.empty((model.body_count, 3), dtype=np.float32)}
    model.kinematics(q[1], out=single, dtype=np.float32)
    assert np.array_equal(single["origin"], model.kinematics(q[1])["origin"].astype(np.float32))


def test_bvh_walk(mbk_kinematics, tmp_path):
    path = source("test/mocap/131_01.bvh")
    model = mbk_kinematics.load(path, scale=0.056444, body_mass=68.5)
    assert model.body_count > 20 and model.masses.sum() == pytest.approx(68.5)
    q, v, a = random_states(model, 2, seed=7)
    out = model.kinematics(q, v, a)
    assert np.isfinite(out["system_acceleration"]).all()
