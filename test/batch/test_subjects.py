"""mbk batch with files of several units and subjects (doc/batch.md#many-subjects): every
warning mbk bag prints for a file is in summary.csv's `warnings` column and the printed table
(a centimetre file among metre files is not silently ok); --subjects FILE.csv gives each file its
subject's scale, body mass and sex, so that the same folder runs clean in one command, as
direct mbk bag runs with those options; a subjects file with an unknown column or a row naming
no input is one error line, nothing run."""
import os
import subprocess

import pytest

from conftest import batch, mbk_path, output_files, source, summary_rows

from mb_kinematics import batch as mbk_batch

WARNING = "mbk: warning: "


def scaled_copy(src, dst, factor):
    """The BVH file `src` with its lengths (OFFSETs, End Sites and position channels) times
    `factor`: the same walk in another unit."""
    with open(src) as f:
        lines = f.read().split("\n")
    channels, out, motion = [], [], False
    for line in lines:
        words = line.split()
        if motion and words and words[0][0] in "-0123456789.":
            line = " ".join("%.9g" % (float(x) * (factor if c.endswith("position") else 1))
                            for x, c in zip(words, channels))
        elif words and words[0] == "OFFSET":
            line = line[:line.index("OFFSET")] + "OFFSET " + " ".join(
                "%.9g" % (float(x) * factor) for x in words[1:])
        elif words and words[0] == "CHANNELS":
            channels += words[2:]
        elif words and words[0] == "MOTION":
            motion = True
        out.append(line)
    with open(dst, "w") as f:
        f.write("\n".join(out))


@pytest.fixture(scope="module")
def trials(tmp_path_factory):
    """trials/: two walks in metres (m/) and one in centimetres (cm/)."""
    root = tmp_path_factory.mktemp("units") / "trials"
    (root / "m").mkdir(parents=True)
    (root / "cm").mkdir()
    for family in ("lafan1", "mixamo"):
        scaled_copy(source("test/mocap/synthetic/%s_layout_walk.bvh" % family),
                    str(root / "m" / ("%s.bvh" % family)), 0.01)
    scaled_copy(source("test/mocap/synthetic/lafan1_layout_walk.bvh"),
                str(root / "cm" / "walk.bvh"), 1.0)
    return str(root)


def bag_alone(path, out, *options):
    """A direct mbk bag run: its warnings, without the prefix, and its CSV's bytes."""
    done = subprocess.run([mbk_path(), "bag", path, "--csv", out] + list(options),
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    with open(out, "rb") as f:
        return ([line[len(WARNING):] for line in done.stderr.splitlines()
                 if line.startswith(WARNING)], f.read())


def test_a_files_warnings_are_in_the_summary_and_the_table(trials, tmp_path):
    out = str(tmp_path / "out")
    status, table, _ = batch(trials, "--out-dir", out, "--scale", "1", "--body-mass", "70")
    assert status == 0  # warnings are no failure
    rows = {os.path.relpath(r["input"], trials): r for r in summary_rows(out)}
    assert sorted(rows) == ["cm/walk.bvh", "m/lafan1.bvh", "m/mixamo.bvh"]
    for relative, row in rows.items():
        warnings, _ = bag_alone(os.path.join(trials, relative), str(tmp_path / "alone.csv"),
                                "--scale", "1", "--body-mass", "70")
        assert row["status"] == "ok"
        assert row["warnings"] == " | ".join(warnings), relative
    assert rows["m/lafan1.bvh"]["warnings"] == rows["m/mixamo.bvh"]["warnings"] == ""
    cm = rows["cm/walk.bvh"]["warnings"]
    assert "standing height" in cm and "--scale 0.01" in cm  # centimetres read as metres
    assert "3 files in " in table and ", 1 with warnings" in table
    listed = [line for line in table.splitlines() if line.startswith("warning ")]
    assert listed == ["warning %s: %s" % (rows["cm/walk.bvh"]["input"], w)
                      for w in cm.split(" | ")]


def test_subjects_give_each_file_its_units_and_body(trials, tmp_path):
    subjects = tmp_path / "subjects.csv"
    subjects.write_text("path,scale,body_mass,sex\n%s/cm/*.bvh,0.01,82.5,female\n"
                        "%s/m/mixamo.bvh,,61,\n" % (trials, trials))
    out = str(tmp_path / "out")
    status, table, _ = batch(trials, "--out-dir", out, "--scale", "1", "--body-mass", "70",
                             "--subjects", str(subjects))
    assert status == 0 and "with warnings" not in table
    assert all(r["warnings"] == "" for r in summary_rows(out))
    outputs = output_files(out)
    for relative, options in (("cm/walk", ["--scale", "0.01", "--body-mass", "82.5", "--sex",
                                           "female"]),
                              ("m/mixamo", ["--scale", "1", "--body-mass", "61"]),
                              ("m/lafan1", ["--scale", "1", "--body-mass", "70"])):
        _, expected = bag_alone(os.path.join(trials, relative + ".bvh"),
                                str(tmp_path / "alone.csv"), *options)
        assert outputs[relative + ".csv"] == expected, relative
    # The same from Python, relative paths from the subjects file's folder.
    (tmp_path / "trials").symlink_to(trials)
    subjects.write_text("path,scale,body_mass,sex\ntrials/cm/walk.bvh,0.01,82.5,female\n")
    rows = mbk_batch.run([trials], str(tmp_path / "py"), scale=1, body_mass=70,
                         subjects=str(subjects))
    assert [r["warnings"] for r in rows] == ["", "", ""]
    assert output_files(str(tmp_path / "py"))["cm/walk.csv"] == outputs["cm/walk.csv"]


@pytest.mark.parametrize("text, error", [
    ("path,scale,age\nx.bvh,1,30\n",
     "subjects.csv: unknown column 'age' (the columns: path, scale, body_mass, sex)"),
    ("scale\n1\n", "subjects.csv: no column 'path' (the columns: path, scale, body_mass, sex)"),
    ("path,scale\nnone/*.bvh,0.01\n", "subjects.csv:2: {dir}/none/*.bvh names no input"),
    ("path,scale\ncm/walk.bvh,-1\n", "subjects.csv:2: --scale needs metres per file unit > 0"),
    ("path,scale\ncm/walk.bvh,1x\n", "subjects.csv:2: --scale needs a number, not '1x'"),
    ("path,body_mass\ncm/walk.bvh,-70\n", "subjects.csv:2: --body-mass needs kg >= 0"),
    ("path,sex\ncm/walk.bvh,x\n",
     "subjects.csv:2: sex: 'x' is neither male nor female (de Leva's columns)"),
])
def test_a_bad_subjects_file_is_refused_before_anything_runs(trials, tmp_path, text, error):
    subjects = os.path.join(trials, "subjects.csv")  # beside the trials: paths relative to it
    with open(subjects, "w") as f:
        f.write(text)
    try:
        with pytest.raises(mbk_batch.BatchError) as refused:
            mbk_batch.run([trials], str(tmp_path / "out"), subjects=subjects)
        if "age" in text:  # on the command line: that one line, exit status 125
            status, out, err = batch(trials, "--out-dir", str(tmp_path / "out"), "--subjects",
                                     subjects)
            assert (status, out, err) == (125, "", "mbk: error: %s\n" % refused.value)
    finally:
        os.remove(subjects)
    assert str(refused.value) == os.path.join(trials, error.format(dir=trials))
    assert not os.path.exists(str(tmp_path / "out"))
