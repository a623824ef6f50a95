"""mbk batch on one machine (doc/batch.md): a folder of recordings with a damaged bag among
them, the outputs of one job and of two byte for byte those of direct `mbk bag` runs, the
summary from mbk bag's own --summary-json, the exit status counting the failure."""
import os
import subprocess

from conftest import (CMU_MASS, CMU_SCALE, DAMAGED, PANDA, batch, batch_arguments, mbk_path,
                      output_files, recordings, summary_rows)
from mb_kinematics import _core
from mb_kinematics.batch_job import BVH_OPTIONS, COMMON_OPTIONS


def test_one_job_two_jobs_and_direct_runs_agree(collection, direct_runs, tmp_path):
    one, two = str(tmp_path / "one"), str(tmp_path / "two")
    alone, expected = direct_runs
    status, table, _ = batch(*batch_arguments(collection, one, "--jobs", "1"))
    assert status == 1  # the damaged bag
    assert "failed" in table and DAMAGED in table
    batch(*batch_arguments(collection, two, "--jobs", "2"), check=1)
    outputs = output_files(one)
    assert outputs == output_files(alone)
    assert outputs == output_files(two)
    good = [r for r in expected if r != DAMAGED]
    for relative in good:  # every good recording's CSV and bag, its samples all there
        csv = outputs[os.path.splitext(relative)[0] + ".csv"].decode()
        assert expected[relative]["written"] > 0
        assert csv.count("\n") > expected[relative]["written"]
        assert os.path.splitext(relative)[0] + ".bag" in outputs
    assert not any(name.startswith("arm/damaged") for name in outputs)


def test_summary_rows_are_mbk_bags_own(collection, direct_runs, tmp_path):
    out = str(tmp_path / "out")
    batch(*batch_arguments(collection, out, "--jobs", "2"), check=1)
    rows = summary_rows(out)
    assert [os.path.relpath(r["input"], collection) for r in rows] == recordings(collection)
    for row in rows:
        relative = os.path.relpath(row["input"], collection)
        expected = direct_runs[1][relative]
        assert row["status"] == expected["status"], row
        assert row["error"] == expected["error"].replace(os.path.join(collection, relative),
                                                         row["input"])
        assert int(row["samples_read"]) == expected["read"]
        assert int(row["samples_written"]) == expected["written"]
        assert int(row["dropped"]) == expected["dropped"]
        assert row["estimator"] == expected["estimator"]
        noise = expected["noise_level"]
        assert row["noise_level"] == ("" if noise is None else repr(noise))
        stem = os.path.join(out, os.path.splitext(relative)[0])
        assert row["output"] == stem + ".bag " + stem + ".csv"
        assert row["resumed"] == "0"
    failed = [r for r in rows if r["status"] != "ok"]
    assert [os.path.relpath(r["input"], collection) for r in failed] == [DAMAGED]
    assert "damaged or truncated bag" in failed[0]["error"]


def test_failures_counted_in_the_exit_status(collection, tmp_path):
    # Without --model the bags and the CSV fail (no model), the BVH files are their own models.
    status, _, progress = batch(collection, "--out-dir", str(tmp_path / "out"), "--scale",
                                "0.056444", "--progress")
    assert status == 4
    rows = summary_rows(str(tmp_path / "out"))
    failed = [r for r in rows if r["status"] == "failed"]
    assert len(failed) == 4 and all("needs --model" in r["error"] for r in failed)
    assert "mbk batch: 8/8 files (4 not ok), " in progress.split("\r")[-1]


def test_list_file_and_single_files(collection, tmp_path):
    listing = tmp_path / "list.txt"
    walks = os.path.join(collection, "walks")
    listing.write_text("# two walks\n%s\n\nsynthetic\n" % os.path.join(walks, "131_01.bvh"))
    os.symlink(os.path.join(walks, "synthetic"), str(tmp_path / "synthetic"))
    out = str(tmp_path / "out")
    batch(str(listing), os.path.join(collection, "arm", "reach.bag"), "--out-dir", out,
          "--model", PANDA, "--scale", "0.056444", "--bag", "--csv", check=0)
    names = sorted(n for n in output_files(out) if not n.endswith("errors.csv"))
    assert names == ["131_01.bag", "131_01.csv", "bandai_layout_walk.bag",
                     "bandai_layout_walk.csv", "lafan1_layout_walk.bag", "lafan1_layout_walk.csv",
                     "mixamo_layout_walk.bag", "mixamo_layout_walk.csv", "reach.bag", "reach.csv"]


def test_bad_command_lines(collection, tmp_path):
    status, out, _ = batch("--help")
    assert status == 0 and out.startswith("usage: mbk batch ")
    status, out, err = batch(str(tmp_path / "missing"), "--out-dir", str(tmp_path / "o"))
    assert (status, out) == (125, "")
    assert err == "mbk: error: %s: no such file or folder\n" % (tmp_path / "missing")
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    for folder in ("a", "b"):
        (tmp_path / folder / "walk.bvh").write_text("")
    status, _, err = batch(str(tmp_path / "a"), str(tmp_path / "b"), "--out-dir",
                           str(tmp_path / "o"))
    assert status == 125 and "both would be written as walk" in err
    status, _, err = batch(collection, "--out-dir", str(tmp_path / "o"), "--jobs", "0")
    assert status == 125 and "--jobs" in err
    (tmp_path / "summary.bvh").write_text("")
    status, _, err = batch(str(tmp_path / "summary.bvh"), "--out-dir", str(tmp_path / "o"))
    assert status == 125 and err.startswith("mbk: error: summary.csv and ")
    assert not os.path.exists(str(tmp_path / "o"))


def test_summary_json_is_the_printed_summary(tmp_path):
    """mbk bag --summary-json against its printed summary, on a trajectory with two drops."""
    import json
    import re
    import subprocess
    from conftest import mbk_path, write_arm_csv
    folder = tmp_path / "in"
    folder.mkdir()
    path = str(folder / "drops.csv")
    write_arm_csv(path, samples=100)
    with open(path, "a") as f:
        f.write("0.5" + ",0.1" * 8 + "\n")  # backwards
        f.write("2.5,nan" + ",0.1" * 7 + "\n")
    done = subprocess.run([mbk_path(), "bag", path, "--model", PANDA, "--csv",
                           str(tmp_path / "out.csv"), "--summary-json",
                           str(tmp_path / "s.json")], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    with open(str(tmp_path / "s.json")) as f:
        summary = json.load(f)
    printed = re.match(r"mbk bag: (\d+) samples read, (\d+) written, (\d+) dropped "
                       r"\(estimator (\w+)", done.stderr).groups()
    assert printed == (str(summary["read"]), str(summary["written"]), str(summary["dropped"]),
                       summary["estimator"])
    drops = dict((cause, int(n)) for n, cause in
                 re.findall(r"  dropped (\d+): (.*) \(first: ", done.stderr))
    assert summary["drops"] == drops and len(drops) == 2
    noise = float(re.search(r"noise level (\S+) ", done.stderr).group(1))
    assert abs(summary["noise_level"] - noise) <= 0.005 * noise
    assert (summary["status"], summary["outputs"]) == ("ok", [str(tmp_path / "out.csv")])
    batch(str(folder), "--out-dir", str(tmp_path / "b"), "--model", PANDA, check=0)
    row, = summary_rows(str(tmp_path / "b"))
    assert row["drops"] == "; ".join("%s: %d" % d for d in sorted(drops.items()))


def test_partial_recording_counted_and_resumed(tmp_path):
    """A bag with messages of another type on /joint_states: mbk bag skips and counts them
    (exit status 2, partial); its row says why, it counts in the exit status, and a second run
    resumes it as it was (finished: the same input gives the same partial output)."""
    import rosbag
    from std_msgs.msg import String
    from conftest import write_arm_bag
    folder = tmp_path / "in"
    folder.mkdir()
    write_arm_bag(str(folder / "good.bag"))
    write_arm_bag(str(folder / "mixed.bag"))
    with rosbag.Bag(str(folder / "mixed.bag"), "a") as bag:
        import rospy
        for t in (1.5, 2.5):
            bag.write("/joint_states", String(data="not a joint state"), rospy.Time.from_sec(t))
    out = str(tmp_path / "out")
    for resumed in ("0", "1"):
        status, table, _ = batch(str(folder), "--out-dir", out, "--model", PANDA)
        assert status == 1
        good, mixed = summary_rows(out)
        assert (good["status"], mixed["status"]) == ("ok", "partial")
        assert mixed["error"].startswith("unreadable 2 messages, skipped")
        assert "partial %s: unreadable 2 messages" % mixed["input"] in table
        assert int(mixed["samples_written"]) == int(good["samples_written"]) == 300
        assert (good["resumed"], mixed["resumed"]) == (resumed, resumed)


def test_table_lists_the_first_failures():
    from mb_kinematics.batch import format_table
    rows = [{"input": "f%d.bag" % i, "status": "failed", "resumed": 0, "samples_read": 0,
             "samples_written": 0, "error": "e%d" % i} for i in range(25)]
    lines = format_table(rows, 1.0).splitlines()
    assert lines[1].split() == ["failed", "25", "0", "0", "0"]
    assert lines[3:] == ["failed f%d.bag: e%d" % (i, i) for i in range(20)] + [
        "... and 5 more in summary.csv"]


def test_summary_json_of_a_failure_is_json(tmp_path):
    """A failed run's --summary-json: the one-line error, the input's name escaped (quotes,
    a line break, a byte that is not UTF-8)."""
    import json
    import subprocess
    from conftest import mbk_path
    name = os.path.join(str(tmp_path), 'no "such"\nwalk\udcff.bvh')  # \udcff: byte 0xff
    summary = str(tmp_path / "s.json")
    done = subprocess.run([mbk_path(), "bag", name.encode("utf-8", "surrogateescape"), "--csv",
                           str(tmp_path / "o.csv"), "--summary-json", summary],
                          capture_output=True)
    assert done.returncode == 1
    with open(summary, encoding="utf-8") as f:
        failed = json.load(f)
    assert failed["status"] == "failed" and failed["written"] == 0
    assert failed["input"] == name.replace("\udcff", "\ufffd")
    assert failed["error"].endswith("cannot open BVH file")
    assert not os.path.exists(str(tmp_path / "o.csv"))


def test_the_jobs_share_the_cores(walk_template, tmp_path, monkeypatch):
    """--jobs N on C cores: each mbk bag runs on C // N threads (at least 1), so that N jobs
    keep the cores busy without contending for them; a given --threads is passed as given."""
    from mb_kinematics import batch, batch_job
    threads, command = [], batch_job._bag_command

    def spy(job):
        line = command(job)
        threads.append(int(line[line.index("--threads") + 1]))
        return line
    monkeypatch.setattr(batch_job, "_bag_command", spy)
    monkeypatch.setattr(batch.os, "sched_getaffinity", lambda pid: {0, 1, 2, 3})
    walk = os.path.join(walk_template[0], "a0.bvh")
    for jobs, given, expected in ((1, None, 4), (2, None, 2), (3, None, 1), (8, None, 1),
                                  (2, 3, 3)):
        del threads[:]
        options = {"threads": given} if given else {}
        rows = batch.run([walk], str(tmp_path / ("%d-%s" % (jobs, given))), jobs=jobs,
                         scale=CMU_SCALE, body_mass=CMU_MASS, **options)
        assert [r["status"] for r in rows] == ["ok"]
        assert threads == [expected], (jobs, given)


def test_every_option_of_mbk_bags_table_reaches_its_usage_and_mbk_batch():
    """mbk bag's one table of options (tools/bag_cli.cc), read through the module: every row is
    in `mbk bag --help` (as `[--name VALUE]`); those mbk batch passes on are its options, with
    the same value, to every job or to .bvh jobs, and in `mbk batch --help`; `mbk --help` points
    to `mbk bag --help`. A new row of the table reaches all of them."""
    rows = _core.bag_options()
    assert len(rows) > 20 and ("--estimator", "NAME", "every job") in rows
    usage = subprocess.run([mbk_path(), "bag", "--help"], capture_output=True, text=True).stdout
    batch_help = batch("--help", check=0)[1]
    for name, value, use in rows:
        assert "[%s]" % " ".join(filter(None, (name, value))) in usage, (name, usage)
        passed = {"every job": COMMON_OPTIONS, "bvh jobs": BVH_OPTIONS}.get(use, {})
        assert (name in COMMON_OPTIONS or name in BVH_OPTIONS) == (use != "bag alone"), name
        if use != "bag alone":
            assert passed[name] == value and name in batch_help, name
    assert "(mbk bag --help)" in subprocess.run([mbk_path(), "--help"], capture_output=True,
                                                text=True).stdout
