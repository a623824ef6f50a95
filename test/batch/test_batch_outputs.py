"""mbk batch --h5 --mot and batch.run(kinds=...): each job's HDF5 and OpenSim files those of a
direct `mbk bag` run, byte for byte (an HDF5 file holds no times: the same run, the same
bytes)."""
import os
import subprocess

from conftest import bag_arguments, batch, mbk_path, output_files, recordings


def test_h5_and_mot_outputs_as_mbk_bags(walk_template, tmp_path):
    folder, _ = walk_template
    alone = str(tmp_path / "alone")
    for relative in recordings(folder):
        stem = os.path.join(alone, os.path.splitext(relative)[0])
        os.makedirs(os.path.dirname(stem), exist_ok=True)
        subprocess.run([mbk_path(), "bag", os.path.join(folder, relative), "--h5", stem + ".h5",
                        "--mot", stem + ".mot", "--h5-compression", "1"] +
                       bag_arguments(relative), check=True, capture_output=True)
    out = str(tmp_path / "out")
    batch(folder, "--out-dir", out, "--scale", "0.056444", "--body-mass", "68.5", "--h5",
          "--mot", "--h5-compression", "1", "--jobs", "2", check=0)
    produced = {n: b for n, b in output_files(out).items() if n.endswith((".h5", ".mot"))}
    assert produced == output_files(alone) and len(produced) == 2 * len(recordings(folder))

    from mb_kinematics import batch as python_batch
    rows = python_batch.run([folder], str(tmp_path / "run"), kinds=("h5",), jobs=1,
                            scale=0.056444, body_mass=68.5, h5_compression=1)
    assert all(r["status"] == "ok" for r in rows)
    by_run = {n: b for n, b in output_files(str(tmp_path / "run")).items() if n.endswith(".h5")}
    assert by_run == {n: b for n, b in produced.items() if n.endswith(".h5")}


def test_column_options_reach_every_job(walk_template, tmp_path):
    """--angles, --body-axes and --mot-coordinates are mbk batch's too: each job's CSV and
    OpenSim file are mbk bag's with the same options, byte for byte."""
    folder, _ = walk_template
    columns = ["--angles", "ZXY", "--body-axes", "--mot-coordinates"]
    alone = str(tmp_path / "alone")
    for relative in recordings(folder):
        stem = os.path.join(alone, os.path.splitext(relative)[0])
        os.makedirs(os.path.dirname(stem), exist_ok=True)
        subprocess.run([mbk_path(), "bag", os.path.join(folder, relative), "--csv", stem + ".csv",
                        "--mot", stem + ".mot"] + columns + bag_arguments(relative),
                       check=True, capture_output=True)
    out = str(tmp_path / "out")
    batch(folder, "--out-dir", out, "--scale", "0.056444", "--body-mass", "68.5", "--csv",
          "--mot", "--jobs", "2", *columns, check=0)
    produced = output_files(out)  # with each CSV its side files of error bars
    assert produced == output_files(alone)
    assert sum(n.endswith(".mot") for n in produced) == len(recordings(folder))
    assert b"angle_order" in produced["a0.csv"] and b"omega_body_x" in produced["a0.csv"]

    from mb_kinematics import batch as python_batch
    rows = python_batch.run([folder], str(tmp_path / "run"), kinds=("mot",), jobs=1,
                            scale=0.056444, body_mass=68.5, angles="ZXY", mot_coordinates=True)
    assert all(r["status"] == "ok" for r in rows)
    by_run = {n: b for n, b in output_files(str(tmp_path / "run")).items() if n.endswith(".mot")}
    assert by_run == {n: b for n, b in produced.items() if n.endswith(".mot")}


def test_column_options_without_their_output_are_refused_before_any_job(walk_template,
                                                                         tmp_path):
    from mb_kinematics.batch import USAGE_STATUS
    folder, _ = walk_template
    for option, message in ((["--body-axes"], "--body-axes adds columns to the CSV: give --csv\n"),
                            (["--mot-coordinates"], "--mot-coordinates adds columns to the "
                             "OpenSim file: give --mot\n"),
                            (["--angles", "ZXY"], "--angles sets the joint angles of the CSV and "
                             "the OpenSim file: give --csv or --mot\n")):
        out = str(tmp_path / ("out" + option[0]))
        status, _, err = batch(folder, "--out-dir", out, "--scale", "0.056444", "--h5", *option)
        assert status == USAGE_STATUS and message in err, err
        assert not os.path.exists(out) or not output_files(out)
