"""mbk batch interrupted (SIGINT, SIGTERM, SIGKILL) and run again: what finished is skipped and
recorded as resumed, nothing half-written counts, and a changed input or option is done again;
the outputs in the end those of direct `mbk bag` runs, byte for byte (doc/batch.md)."""
import glob
import os
import shutil
import signal
import subprocess
import time

import psutil
import pytest

from conftest import CMU_MASS, CMU_SCALE, batch, mbk_path, output_files, summary_rows

@pytest.fixture
def walks(walk_template, tmp_path):
    shutil.copytree(walk_template[0], str(tmp_path / "walks"))
    return str(tmp_path / "walks")


@pytest.fixture
def expected(walk_template):
    return walk_template[1]


def arguments(walks, out, *more):
    return [walks, "--out-dir", out, "--jobs", "1", "--scale", CMU_SCALE, "--body-mass",
            CMU_MASS] + list(more)


def records(out):
    return glob.glob(os.path.join(out, ".mbk-batch", "**", "*.json"), recursive=True)


def running_mbk_bag(batch_process):
    """(process, command line) of an mbk bag run the batch has started, or None."""
    for process in psutil.Process(batch_process.pid).children(recursive=True):
        try:
            command = " ".join(process.cmdline())
        except psutil.NoSuchProcess:
            continue
        if "mbk_bag" in command:
            return process, command
    return None


def interrupt(walks, out, signum):
    """Starts mbk batch, sends `signum` once two files are done and a third is running; its
    exit status."""
    child = subprocess.Popen([mbk_path(), "batch"] + arguments(walks, out),
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 60
    while child.poll() is None and time.monotonic() < deadline:
        if len(records(out)) >= 2 and running_mbk_bag(child):
            break
        time.sleep(0.01)
    child.send_signal(signum)
    child.communicate(timeout=60)
    return child.returncode


def no_temporaries(out):
    return not glob.glob(os.path.join(out, "**", "*mbk-tmp*"), recursive=True)


@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM])
def test_interrupted_then_resumed(walks, expected, tmp_path, signum):
    out = str(tmp_path / "out")
    assert interrupt(walks, out, signum) == 128 + signum
    assert no_temporaries(out)
    rows = summary_rows(out)
    done = [r["input"] for r in rows if r["status"] == "ok"]
    assert 2 <= len(done) < len(rows) == 6
    assert {r["status"] for r in rows} == {"ok", "not run"}
    want = expected
    for name, data in output_files(out).items():
        assert data == want[name], name  # what is there is whole
    status, _, _ = batch(*arguments(walks, out))
    assert status == 0
    rows = summary_rows(out)
    assert [r["input"] for r in rows if r["resumed"] == "1"] == done
    assert all(r["status"] == "ok" for r in rows)
    assert output_files(out) == want
    assert no_temporaries(out)


def test_killed_batch_leaves_nothing_half_written(walks, expected, tmp_path):
    """SIGKILL: no summary, no handler; the running mbk bag ends with the batch (its parent
    death signal) and removes its temporary file."""
    out = str(tmp_path / "out")
    assert interrupt(walks, out, signal.SIGKILL) == -signal.SIGKILL
    time.sleep(0.5)
    assert no_temporaries(out)
    assert not os.path.exists(os.path.join(out, "summary.csv"))
    batch(*arguments(walks, out), check=0)
    rows = summary_rows(out)
    assert sum(r["resumed"] == "1" for r in rows) >= 2
    assert output_files(out) == expected


def test_changed_input_option_or_output_is_done_again(walks, expected, tmp_path):
    out = str(tmp_path / "out")
    batch(*arguments(walks, out), check=0)
    shutil.copy(os.path.join(walks, "b", "c0.bvh"), os.path.join(walks, "a0.bvh"))  # new content
    with open(os.path.join(out, "b", "c1.csv"), "r+b") as f:  # an output cut short
        f.truncate(1000)
    os.remove(os.path.join(out, "b", "c2.csv"))
    batch(*arguments(walks, out), check=0)
    rows = {os.path.relpath(r["input"], walks): r for r in summary_rows(out)}
    again = sorted(name for name, r in rows.items() if r["resumed"] == "0")
    assert again == ["a0.bvh", "b/c1.bvh", "b/c2.bvh"]
    want = dict(expected)
    for name in ("a0.csv", "a0.errors.csv", "a0.sample_errors.csv"):
        want[name] = expected["b/c0" + name[2:]]
    assert output_files(out) == want
    batch(*arguments(walks, out, "--max-gap", "0.2"), check=0)  # another option: all again
    assert all(r["resumed"] == "0" for r in summary_rows(out))
    batch(*arguments(walks, out, "--max-gap", "0.2", "--jobs", "2"), check=0)  # jobs: the same
    assert all(r["resumed"] == "1" for r in summary_rows(out))


def test_a_crashed_job_fails_alone_and_is_done_again(walks, expected, tmp_path):
    """An mbk bag run killed (SIGKILL, as a crash) while the batch goes on: its row is failed,
    naming the signal, the others are done; the next run does that one only."""
    out = str(tmp_path / "out")
    child = subprocess.Popen([mbk_path(), "batch"] + arguments(walks, out),
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    crashed = None
    while crashed is None and child.poll() is None:
        running = running_mbk_bag(child) if records(out) else None
        try:
            if running:
                running[0].kill()
                crashed = running[1]
        except psutil.NoSuchProcess:  # it ended first: the next one
            pass
        time.sleep(0.01)
    child.communicate(timeout=60)
    assert child.returncode == 1 and crashed is not None
    rows = summary_rows(out)
    failed = [r for r in rows if r["status"] == "failed"]
    assert len(failed) == 1 and failed[0]["error"].startswith("mbk bag ended by SIGKILL")
    assert failed[0]["input"] in crashed
    assert all(r["status"] == "ok" for r in rows if r is not failed[0])
    batch(*arguments(walks, out), check=0)
    rows = summary_rows(out)
    assert [r["input"] for r in rows if r["resumed"] == "0"] == [failed[0]["input"]]
    assert output_files(out) == expected


def test_a_jobs_record_is_renamed_into_place_without_a_sync(walks, tmp_path, monkeypatch):
    """A finished job's record is whole (renamed into place) and skips the job next time, but is
    not synced to the disk: losing it to a power cut only runs the job again. It is the job's
    only file besides the outputs: mbk bag's summary comes on its stdout, no file to remove."""
    from mb_kinematics import batch_job
    synced, removed = [], []
    monkeypatch.setattr(batch_job.os, "fsync", synced.append)
    monkeypatch.setattr(batch_job.os, "remove", removed.append)
    options = {"--scale": CMU_SCALE, "--body-mass": CMU_MASS}
    out = str(tmp_path / "out")
    job = batch_job.plan([(os.path.join(walks, "a0.bvh"), "a0")], out, options)[0]
    assert batch_job.run_job(job)["status"] == "ok"
    assert batch_job.finished(job)["written"] == 300
    assert synced == [] and removed == []
    assert os.listdir(os.path.join(out, ".mbk-batch")) == ["a0.json"]


def test_a_rebuilt_library_of_mbk_bag_makes_the_jobs_run_again(walks, tmp_path):
    """The key holds the package's libraries beside mbk_bag (its code), not only the executable:
    a rebuilt libmbk_offline.so changes the outputs as a rebuilt mbk_bag does."""
    from mb_kinematics import batch_job
    lib = tmp_path / "lib"
    (lib / "mb_kinematics").mkdir(parents=True)
    mbk_bag, library = lib / "mb_kinematics" / "mbk_bag", lib / "libmbk_offline.so"
    mbk_bag.write_bytes(b"the executable")
    library.write_bytes(b"the code")

    def key():
        return batch_job.plan([(os.path.join(walks, "a0.bvh"), "a0")], str(tmp_path / "out"), {},
                              mbk_bag=str(mbk_bag))[0]["key"]
    before = key()
    assert key() == before
    library.write_bytes(b"the code, rebuilt")
    assert key() != before
