"""Hostile input to the Python module and to `mbk bag` / `mbk eval` (doc/reliability.md): threads
that cannot start, a recording given to another model, out= arrays that overlap the inputs or
each other, arguments of the wrong kind or beyond a double, inputs that are not regular files,
states without end. Each must end in one clear error or the right numbers, never an abort, a
hang or a wrong array."""
import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest

from conftest import mbk_path, random_states, source

PANDA = source("test/robots/panda.urdf")
HUMAN = source("config/human_body.urdf")


def run_python(code, timeout=120):
    """`code` in a fresh interpreter with this one's path (the devel space's package)."""
    return subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True,
                          text=True, timeout=timeout, env=dict(os.environ))


def run_mbk(*args, stdin=None, timeout=60):
    return subprocess.run([mbk_path()] + list(args), capture_output=True, text=True,
                          stdin=stdin, timeout=timeout)


def arm_csv(path, rows=200, start=1.0):
    model_names = ["panda_joint%d" % j for j in range(1, 8)] + ["panda_finger_joint1"]
    t = start + np.arange(rows) * 0.01
    with open(path, "w") as f:
        f.write(",".join(["time"] + model_names) + "\n")
        for ti in t:
            f.write("%.9f," % ti + ",".join("%.12f" % (0.3 * np.sin((1 + 0.2 * j) * ti))
                                            for j in range(8)) + "\n")
    return path


@pytest.fixture(scope="module")
def panda(mbk_kinematics):
    return mbk_kinematics.load(PANDA)


@pytest.fixture(scope="module")
def human(mbk_kinematics):
    return mbk_kinematics.load(HUMAN)


# --- Threads that cannot start ----------------------------------------------------------------

@pytest.mark.skipif("asan" in os.environ.get("LD_PRELOAD", ""),
                    reason="AddressSanitizer's shadow rules out an address space cap")
def test_threads_that_cannot_start_shrink_the_pool():
    """1,000 threads under an address space 512 MB above what the process holds (their 8 MB
    stacks do not fit): the same arrays as on one thread, no abort."""
    done = run_python("""
        import resource, numpy as np, mb_kinematics
        model = mb_kinematics.load(%r)
        q = np.random.default_rng(1).uniform(-1, 1, (1000, model.nq))
        one = model.kinematics(q, threads=1)
        size = int(open("/proc/self/statm").read().split()[0]) * resource.getpagesize()
        resource.setrlimit(resource.RLIMIT_AS, (size + (512 << 20), resource.RLIM_INFINITY))
        many = model.kinematics(q, threads=1000)
        assert all(np.array_equal(one[k], many[k]) for k in one), "other numbers"
        print("same")
        """ % HUMAN)
    assert done.returncode == 0, done.stderr
    assert done.stdout == "same\n"


def test_mbk_bag_threads_beyond_the_address_space(tmp_path):
    """mbk bag --threads 1024 under --max-memory 2, 4, 8 and 16 GiB (the stacks alone take 8):
    the run completes on the threads that started, as on one thread, or stops with the one line
    of --max-memory; never an abort, and no temporary is left. Which limits complete depends on
    what the build maps (the libraries' address space): 16 GiB always leaves room. The pool's
    shrinking itself: split_runs_test ThreadsThatCannotStartShrinkThePool."""
    csv = arm_csv(str(tmp_path / "t.csv"))
    one = str(tmp_path / "one.csv")
    first = run_mbk("bag", csv, "--model", PANDA, "--csv", one, "--threads", "1")
    assert first.returncode == 0, first.stderr
    completed = 0
    for gib in ("2", "4", "8", "16"):
        many = str(tmp_path / ("many%s.csv" % gib))
        run = run_mbk("bag", csv, "--model", PANDA, "--csv", many, "--threads", "1024",
                      "--max-memory", gib)
        assert run.returncode in (0, 1), run.stderr
        if run.returncode == 0:
            completed += 1
            assert open(one).read() == open(many).read()
        else:
            assert run.stderr == ("mbk: error: out of memory: the run needs more than "
                                  "--max-memory %s GiB of address space (default: 90 %% of this "
                                  "machine's memory); give a larger --max-memory or fewer "
                                  "--threads\n" % gib)
        assert not [f for f in os.listdir(str(tmp_path)) if "mbk-tmp" in f]
    assert completed >= 1


# --- Recordings and models --------------------------------------------------------------------

def test_a_recording_of_another_model_is_refused(panda, human, tmp_path):
    recording = panda.read_recording(arm_csv(str(tmp_path / "arm.csv")))
    for call in (lambda: human.states(recording), lambda: human.recording_kinematics(recording)):
        with pytest.raises(ValueError, match="read for another model"):
            call()
    twin = human.recording(np.arange(5.0), np.tile(human.neutral_position, (5, 1)))
    with pytest.raises(ValueError, match="read for another model"):
        panda.states(twin)
    again = type(panda)(panda._core)  # the same model: accepted
    assert again.states(recording)["valid"].any()


def test_an_empty_model_text_is_refused(mbk_kinematics):
    for text in ("\n" * 100, " \t\r\n"):
        with pytest.raises(ValueError, match="an empty model text"):
            mbk_kinematics.load(text)


# --- out= arrays that overlap -----------------------------------------------------------------

def test_out_overlapping_an_input_gives_the_right_numbers(human):
    q, v, a = random_states(human, 20, seed=4)
    expected = human.kinematics(q, v, a, outputs=["origin", "mass_center"])
    n, b = len(q), human.body_count
    buffer = np.zeros(n * b * 3 + 10)
    shared_q = buffer[:q.size].reshape(q.shape)  # origin's first elements are q's
    shared_q[:] = q
    origin = buffer[:n * b * 3].reshape(n, b, 3)
    human.kinematics(shared_q, v, a, outputs=["origin"], out={"origin": origin})
    assert np.array_equal(origin, expected["origin"])
    buffer = np.zeros(n * b * 3 + 10)
    shared_v = buffer[5:5 + v.size].reshape(v.shape)
    shared_v[:] = v
    center = buffer[:n * b * 3].reshape(n, b, 3)
    human.kinematics(q, shared_v, a, outputs=["mass_center"], out={"mass_center": center})
    assert np.array_equal(center, expected["mass_center"])


def test_out_arrays_overlapping_each_other_are_refused(human):
    q, _, _ = random_states(human, 3, seed=5)
    n, b = len(q), human.body_count
    buffer = np.full(2 * n * b * 3, 7.0)
    out = {"origin": buffer[:n * b * 3].reshape(n, b, 3),
           "mass_center": buffer[3:3 + n * b * 3].reshape(n, b, 3)}
    with pytest.raises(ValueError, match=r"out\['origin'\] and out\['mass_center'\]: overlap"):
        human.kinematics(q, out=out)
    assert (buffer == 7.0).all()


def test_out_arrays_off_a_doubles_boundary_give_the_right_numbers(mbk_kinematics, human):
    # numpy takes float64 arrays at any byte (np.frombuffer at an odd offset; flags.aligned is
    # False); outputs this large (17 MB) are streamed, eight samples at once on AVX-512F CPUs.
    q, v, a = random_states(human, 1100, seed=6)
    names = [k for k in mbk_kinematics.OUTPUTS if not k.startswith("partial_")]
    expected = human.kinematics(q, v, a, outputs=names)
    for offset in (1, 4, 8):
        out = {}
        for name, x in expected.items():
            raw = bytearray(x.nbytes + offset)
            out[name] = np.frombuffer(raw, np.float64, x.size, offset).reshape(x.shape)
        human.kinematics(q, v, a, outputs=names, out=out, threads=2)
        for name, x in expected.items():
            assert np.array_equal(out[name], x, equal_nan=True), (name, offset)


# --- Arguments of the wrong kind --------------------------------------------------------------

def test_a_nul_in_a_path_is_refused(mbk_kinematics, panda, tmp_path):
    with pytest.raises(ValueError, match="NUL"):
        mbk_kinematics.load(PANDA + "\0.yaml")
    csv = arm_csv(str(tmp_path / "arm.csv"))
    with pytest.raises(ValueError, match="NUL"):
        panda.read_recording(csv + "\0.csv")


def test_scales_and_numbers_out_of_range(mbk_kinematics):
    walk = source("test/mocap/131_01.bvh")
    model = mbk_kinematics.load(walk, scale=0.056444)
    for scale in (0, -1, float("inf")):
        with pytest.raises(ValueError, match="scale"):
            model.read_recording(walk, scale=scale)
    for call in (lambda: mbk_kinematics.load(walk, scale=10 ** 400),
                 lambda: model.read_recording(walk, scale=10 ** 400)):
        with pytest.raises(ValueError, match=r"scale: .* beyond a double's range"):
            call()
    with pytest.raises(TypeError, match="scale: a number, not bool"):
        model.read_recording(walk, scale=True)


def test_denormal_time_steps_are_not_valid_rows(panda):
    t = np.arange(40) * 5e-324  # subnormal steps: 1/dt overflows
    q = np.tile(panda.neutral_position, (40, 1)) + 0.01 * np.arange(40)[:, None]
    states = panda.states(panda.recording(t, q), estimator="centered_5_2")
    assert not states["valid"].any()
    for r in np.flatnonzero(states["valid"]):
        assert np.isfinite(states["velocity"][r]).all()


def test_max_gap_zero_and_bools(panda):
    recording = panda.recording(np.arange(10.0), np.tile(panda.neutral_position, (10, 1)))
    for gap in (0, -1, float("nan")):
        with pytest.raises(ValueError, match="max_gap: .*expected seconds above 0"):
            panda.states(recording, max_gap=gap)
    q = np.zeros((2, panda.nq))
    with pytest.raises(TypeError, match="bodies: body names or indices, not bool"):
        panda.kinematics(q, bodies=True)
    with pytest.raises(TypeError, match="bodies: a body name or index, not bool"):
        panda.kinematics(q, bodies=[True])
    with pytest.raises(TypeError, match="threads: an integer, not bool"):
        panda.kinematics(q, threads=True)
    with pytest.raises(ValueError, match="threads: 2147483648, expected 1 to 1024"):
        panda.kinematics(q, threads=2 ** 31)


def test_a_model_without_coordinates(mbk_kinematics):
    model = mbk_kinematics.load("frame: R\nbodies:\n  - {name: box, lower: 0, joint: {name: j, "
                                "type: fixed, origin: [0, 0, 1]}, mass_center: [0, 0, 0], "
                                "mass: 1}\n")
    assert model.nq == 0
    one = model.kinematics(np.zeros(0))
    assert one["origin"].shape == (model.body_count, 3)
    many = model.kinematics(np.zeros((4, 0)))
    assert many["origin"].shape == (4, model.body_count, 3)


def test_read_only_attributes_stay_read_only(panda):
    for name in ("masses", "mass_centers", "lower", "neutral_position", "lower_table"):
        array = getattr(panda, name)
        with pytest.raises(ValueError):
            array.setflags(write=True)
        with pytest.raises(ValueError):
            array[...] = 0


# --- Inputs that are not regular files, states without end ------------------------------------

def not_regular_files(tmp_path):
    """A FIFO and a link to /dev/zero, each named as a CSV recording and as a segment map."""
    fifo, zero = str(tmp_path / "fifo.csv"), str(tmp_path / "zero.csv")
    os.mkfifo(fifo)
    os.symlink("/dev/zero", zero)
    return [fifo, zero]


def test_read_recording_refuses_what_is_not_a_regular_file(tmp_path):
    for path in not_regular_files(tmp_path):
        done = run_python("""
            import mb_kinematics
            model = mb_kinematics.load(%r)
            try:
                model.read_recording(%r)
            except ValueError as e:
                print(e)
            """ % (PANDA, path), timeout=30)
        assert done.stdout == "%s: cannot read the recording: not a regular file (a device, a " \
                              "pipe or a folder)\n" % path, done.stderr


def test_mbk_bag_refuses_what_is_not_a_regular_file(tmp_path):
    out = str(tmp_path / "out.csv")
    for path in not_regular_files(tmp_path):
        run = run_mbk("bag", path, "--model", PANDA, "--csv", out, timeout=30)
        assert run.returncode == 1
        assert run.stderr.endswith("%s: cannot read the recording: not a regular file (a "
                                   "device, a pipe or a folder)\n" % path), run.stderr
        segments = path[:-4] + ".yaml"
        os.rename(path, segments)
        run = run_mbk("bag", source("test/mocap/131_01.bvh"), "--scale", "0.056444",
                      "--body-mass", "68.5", "--segments", segments, "--csv", out, timeout=30)
        assert run.returncode == 1
        assert "%s: cannot read segment map: not a regular file" % segments in run.stderr
        assert not os.path.exists(out)


def test_mbk_eval_state_is_bounded(tmp_path):
    """`--state -` fed without end and a state file of 10 MB: refused at the bound, which the
    message names."""
    with open("/dev/zero") as zero:
        run = run_mbk("eval", "--model", HUMAN, "--state", "-", stdin=zero)
    assert run.returncode == 1
    assert "standard input: a text of more than" in run.stderr, run.stderr
    big = str(tmp_path / "big.json")
    with open(big, "w") as f:
        f.write('{"position": {' + ", ".join('"c%d": 0' % i for i in range(10 ** 6)) + "}}")
    run = run_mbk("eval", "--model", HUMAN, "--state", big)
    assert run.returncode == 1
    assert "%s: state file of more than" % big in run.stderr, run.stderr
    small = str(tmp_path / "small.json")
    with open(small, "w") as f:
        f.write('{"position": {}}' + " " * 100000)  # blanks below the bound: read
    assert run_mbk("eval", "--model", HUMAN, "--state", small).returncode == 0


# --- Wall-clock CSV stamps --------------------------------------------------------------------

def arm_rows(path, first_second):
    """3,000 rows of the Panda arm at 250 Hz from `first_second`, stamps written with 9 decimals
    (the same motion whatever the start): the stamps' texts."""
    names = ["panda_joint%d" % j for j in range(1, 8)] + ["panda_finger_joint1"]
    stamps = []
    with open(path, "w") as f:
        f.write(",".join(["time"] + names) + "\n")
        for i in range(3000):
            stamps.append("%d.%09d" % (first_second + i // 250, (i % 250) * 4000000))
            t = i / 250
            f.write(stamps[-1] + "," + ",".join("%.12f" % (0.3 * np.sin((1 + 0.2 * j) * t))
                                                  for j in range(8)) + "\n")
    return stamps


def test_wall_clock_csv_stamps_are_kept_to_the_nanosecond(panda, tmp_path):
    """Stamps from 1.7e9 s (where a double is 2.4e-7 s apart) come out as they went in, in the
    CSV and a bag, and the accelerations are those of the same rows from 1 s."""
    wall, early = str(tmp_path / "wall.csv"), str(tmp_path / "early.csv")
    stamps = arm_rows(wall, 1700000000)
    arm_rows(early, 1)
    out, bag = str(tmp_path / "out.csv"), str(tmp_path / "out.bag")
    h5, mot = str(tmp_path / "out.h5"), str(tmp_path / "out.mot")
    run = run_mbk("bag", wall, "--model", PANDA, "--csv", out, "--out", bag, "--h5", h5,
                  "--mot", mot)
    assert run.returncode == 0, run.stderr
    with open(out) as f:
        written = sorted({line.split(",", 1)[0] for line in f.readlines()[1:]})
    assert written == stamps
    import h5py
    with h5py.File(h5, "r") as f:  # the CSV's stamps as doubles, not origin + stamp rounded
        assert list(f["time"][:]) == [float(s) for s in stamps]
    with open(mot) as f:
        rows = f.read().split("endheader\n", 1)[1].splitlines()[1:]
    assert [r.split("\t", 1)[0] for r in rows] == stamps
    import rosbag
    with rosbag.Bag(bag) as b:
        times = sorted({"%d.%09d" % (m.header.stamp.secs, m.header.stamp.nsecs)
                        for _, m, _ in b.read_messages(topics=["/body_kinematics"])})
    assert times == stamps
    late = panda.recording_kinematics(panda.read_recording(wall))
    soon = panda.recording_kinematics(panda.read_recording(early))
    assert np.abs(late["time"] - 1700000000 + 1 - soon["time"]).max() <= 2.4e-7  # a double's
    scale = np.abs(soon["acceleration"]).max()
    assert np.abs(late["acceleration"] - soon["acceleration"]).max() <= 1e-6 * scale


def test_csv_times_closer_than_a_nanosecond_are_refused(panda, tmp_path):
    """Times less than 1 ns apart would be written alike (the outputs hold whole nanoseconds):
    the CSV is refused with one line naming the row, and nothing is written."""
    path, out = str(tmp_path / "close.csv"), str(tmp_path / "out.csv")
    with open(path, "w") as f:
        f.write(",".join(["time"] + ["panda_joint%d" % j for j in range(1, 8)] +
                         ["panda_finger_joint1"]) + "\n")
        for i in range(5):
            f.write("%.12f," % (1 + i * 1e-10) + ",".join(["0.1"] * 8) + "\n")
    run = run_mbk("bag", path, "--model", PANDA, "--csv", out)
    assert run.returncode != 0
    assert "close.csv:3: time 1.000000000100 is less than 1 ns after the row before" in \
        run.stderr, run.stderr
    assert len(run.stderr.strip().splitlines()) == 1, run.stderr
    assert not os.path.exists(out)
    with pytest.raises(ValueError, match="less than 1 ns after the row before"):
        panda.read_recording(path)
    spaced = str(tmp_path / "spaced.csv")  # 1 ns apart: read, each stamp as written
    with open(path) as f, open(spaced, "w") as g:
        lines = f.read().splitlines()
        g.write(lines[0] + "\n" + "".join("%.9f," % (1 + i * 1e-9) + l.split(",", 1)[1] + "\n"
                                         for i, l in enumerate(lines[1:])))
    assert run_mbk("bag", spaced, "--model", PANDA, "--csv", out).returncode == 0
