"""mbk batch on hostile collections and clusters (doc/batch.md, doc/reliability.md): side files
of one input named as another input's output, a scheduler or the only worker lost, SIGINT to the
batch and its children together, links that lead nowhere, names that are not UTF-8, an --out-dir
of the wrong kind, a full disk, protocols Dask cannot use. One line or one row each, never a
traceback, a hang or a row that lies."""
import csv
import errno
import os
import signal
import socket
import subprocess
import sys
import threading
import time

import pytest

from conftest import (CMU_MASS, CMU_SCALE, PANDA, batch, mbk_path, summary_rows, trimmed_walk,
                      write_arm_csv)
from mb_kinematics import batch as mbk_batch
from mb_kinematics import batch_job


def walks(folder, count, frames=300):
    """`count` CMU walks (the first `frames` frames of 131_01) in `folder`."""
    os.makedirs(folder, exist_ok=True)
    for i in range(count):
        trimmed_walk("131_01.bvh", os.path.join(folder, "w%02d.bvh" % i), frames)
    return folder


def walk_arguments(folder, out):
    return [folder, "--out-dir", out, "--scale", CMU_SCALE, "--body-mass", CMU_MASS]


# --- Side files -------------------------------------------------------------------------------

def test_an_input_named_as_another_inputs_side_file_is_refused(tmp_path):
    folder = tmp_path / "in"
    folder.mkdir()
    write_arm_csv(str(folder / "x.csv"))
    write_arm_csv(str(folder / "x.errors.csv"))
    status, _, err = batch(str(folder), "--out-dir", str(tmp_path / "out"), "--model", PANDA)
    assert status == 125
    assert err == "mbk: error: %s and %s: both would be written as x.errors in --out-dir\n" % (
        folder / "x.csv", folder / "x.errors.csv")
    assert not (tmp_path / "out").exists()


# --- Dask: a scheduler or the only worker lost ------------------------------------------------

def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def start_cluster(tmp_path):
    """A dask-scheduler and one dask-worker without a nanny (killed, it stays dead), as
    processes of their own: (scheduler, worker, address)."""
    port = free_port()
    address = "tcp://127.0.0.1:%d" % port
    quiet = dict(stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, cwd=str(tmp_path))
    scheduler = subprocess.Popen(["dask-scheduler", "--host", "127.0.0.1", "--port", str(port),
                                  "--dashboard-address", ":0"], **quiet)
    worker = subprocess.Popen(["dask-worker", address, "--no-nanny", "--nthreads", "1"], **quiet)
    from distributed import Client
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:
        try:
            with Client(address, timeout=5) as c:
                if c.scheduler_info()["workers"]:
                    return scheduler, worker, address
        except OSError:
            pass
        time.sleep(0.5)
    raise RuntimeError("no Dask cluster came up")


def stop(*processes):
    for p in processes:
        if p.poll() is None:
            p.kill()
        p.wait()


def when_records(out, count, then):
    """Calls then() once `count` records are under out/.mbk-batch (a thread)."""
    def watch():
        state = os.path.join(out, ".mbk-batch")
        while not (os.path.isdir(state) and len(os.listdir(state)) >= count):
            time.sleep(0.05)
        then()
    threading.Thread(target=watch, daemon=True).start()


def test_a_lost_scheduler_keeps_the_finished_jobs(tmp_path):
    """The scheduler killed after the first records: those jobs are ok (their records and
    outputs are whole), the others failed; before, every row was "failed CancelledError". The
    worker goes with it: a worker that outlives its scheduler finishes the job it holds after
    the batch has reported it failed (its record then appears late; a resumed run skips it)."""
    scheduler, worker, address = start_cluster(tmp_path)
    try:
        folder, out = walks(str(tmp_path / "in"), 12, frames=994), str(tmp_path / "out")
        when_records(out, 2, lambda: (scheduler.kill(), worker.kill()))
        run = subprocess.run([mbk_path(), "batch"] + walk_arguments(folder, out) +
                             ["--scheduler", address], capture_output=True, text=True,
                             timeout=300)
    finally:
        stop(scheduler, worker)
    assert "Traceback" not in run.stderr, run.stderr
    rows = summary_rows(out)
    ok = [r for r in rows if r["status"] == "ok"]
    records = os.listdir(os.path.join(out, ".mbk-batch"))
    assert len(ok) >= 2 and len(ok) == len(records)
    assert sorted(os.path.splitext(os.path.basename(r["input"]))[0] + ".json"
                  for r in ok) == sorted(records)
    assert all(r["status"] == "failed" for r in rows if r not in ok)
    assert run.returncode == len(rows) - len(ok)


def test_no_live_worker_times_out_and_a_signal_stops_the_wait(tmp_path, monkeypatch):
    scheduler, worker, address = start_cluster(tmp_path)
    try:
        folder, out = walks(str(tmp_path / "in"), 4), str(tmp_path / "out")
        stop(worker)  # the only worker, without a nanny: none comes back
        from distributed import Client
        monkeypatch.setattr(mbk_batch, "NO_CLUSTER_SECONDS", 3)
        with Client(address) as client:
            rows = mbk_batch.run([folder], out, client=client, scale=CMU_SCALE,
                                 body_mass=CMU_MASS)
        assert [r["status"] for r in rows] == ["failed"] * 4
        assert {r["error"] for r in rows} == {
            "Dask: no worker alive for 3 s; run again to resume"}
        assert summary_rows(out) == [{k: str(v) for k, v in r.items()} for r in rows]
        # mbk batch waiting on the same cluster (60 s): SIGTERM and SIGINT end it at once.
        for signum in (signal.SIGTERM, signal.SIGINT):
            again = subprocess.Popen([mbk_path(), "batch"] + walk_arguments(folder, out) +
                                     ["--scheduler", address], stdout=subprocess.PIPE,
                                     stderr=subprocess.PIPE, text=True)
            with Client(address) as watch:  # its tasks submitted: it is waiting on them
                while not watch.run_on_scheduler(lambda dask_scheduler: len(dask_scheduler.tasks)):
                    time.sleep(0.1)
            again.send_signal(signum)
            _, err = again.communicate(timeout=30)
            assert again.returncode == 128 + signum, err
            assert err.endswith("finished files are kept, run again to resume\n"), err
            assert [r["status"] for r in summary_rows(out)] == ["not run"] * 4
    finally:
        stop(scheduler, worker)


# --- Ctrl-C -----------------------------------------------------------------------------------

def test_ctrl_c_to_the_batch_and_its_children(tmp_path):
    """SIGINT to the process group while two jobs run: their rows are "not run" (not "failed"),
    every row ok has its record, no job starts after the signal."""
    folder = walks(str(tmp_path / "in"), 12, frames=994)
    for attempt in range(3):
        out = str(tmp_path / ("out%d" % attempt))
        run = subprocess.Popen([mbk_path(), "batch", "--jobs", "2"] +
                               walk_arguments(folder, out), stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True, start_new_session=True)
        state = os.path.join(out, ".mbk-batch")
        deadline = time.monotonic() + 60
        while not (os.path.isdir(state) and os.listdir(state)) and time.monotonic() < deadline:
            time.sleep(0.02)
        os.killpg(run.pid, signal.SIGINT)
        _, err = run.communicate(timeout=60)
        assert run.returncode == 130, err
        rows = summary_rows(out)
        assert {r["status"] for r in rows} <= {"ok", "not run"}, rows
        ok = [r for r in rows if r["status"] == "ok"]
        assert len(ok) == len(os.listdir(state))
        assert len(ok) < len(rows)


def test_a_run_the_signal_ended_is_not_run(monkeypatch):
    """The signal reaches a job's mbk bag and the batch together: that run ends "failed" just as
    the batch learns of the signal; its row must be "not run" (deterministic: the fake job
    delivers the signal itself)."""
    stop = mbk_batch._Stop()
    reported = []

    def ended_by_the_signal(job, running=None, stop_event=None):
        stop._note(signal.SIGINT, None)
        return batch_job.failure(job, "mbk bag ended by SIGINT")
    monkeypatch.setattr(mbk_batch, "run_job", ended_by_the_signal)
    jobs = [{"input": "a.bvh", "outputs": []}]
    with pytest.raises(mbk_batch.Interrupted):
        mbk_batch._run_local(jobs, 1, lambda job, summary: reported.append(summary), stop)
    assert reported == []


def test_no_job_starts_once_stopped(tmp_path):
    stopped = threading.Event()
    stopped.set()
    job = {"record": str(tmp_path / "r.json"), "outputs": [], "input": "x.bvh"}
    assert batch_job.run_job(job, set(), stopped) is None
    assert os.listdir(str(tmp_path)) == []


# --- One line instead of a traceback ----------------------------------------------------------

def test_links_that_lead_nowhere(tmp_path):
    folder = walks(str(tmp_path / "in"), 1)
    os.symlink(os.path.join(folder, "missing.bvh"), os.path.join(folder, "dangling.bvh"))
    status, _, err = batch(*walk_arguments(folder, str(tmp_path / "out")))
    assert (status, err) == (125, "mbk: error: %s/dangling.bvh: No such file or directory\n"
                             % folder)
    os.remove(os.path.join(folder, "dangling.bvh"))
    os.symlink("loop.csv", os.path.join(folder, "loop.csv"))
    status, _, err = batch(*walk_arguments(folder, str(tmp_path / "out")))
    assert (status, err) == (125, "mbk: error: %s/loop.csv: Too many levels of symbolic links\n"
                             % folder)


def test_a_name_that_is_not_utf8(tmp_path):
    folder = walks(str(tmp_path / "in"), 1)
    name = os.path.join(os.fsencode(folder), b"caf\xe9.bvh")
    os.rename(os.path.join(folder, "w00.bvh"), name)
    out = str(tmp_path / "out")
    done = subprocess.run([mbk_path(), "batch"] + walk_arguments(folder, out),
                          capture_output=True)
    assert done.returncode == 0, done.stderr
    assert done.stderr == b""
    assert b"caf\xe9.bvh" in done.stdout or b"1 files" in done.stdout
    with open(os.path.join(out, "summary.csv"), "rb") as f:
        assert name in f.read()
    assert os.path.exists(os.path.join(os.fsencode(out), b"caf\xe9.csv"))
    assert not [f for f in os.listdir(out) if "mbk-tmp" in f]


def test_an_out_dir_of_the_wrong_kind(tmp_path):
    folder = walks(str(tmp_path / "in"), 1)
    out = tmp_path / "out"
    out.write_text("a file")
    status, _, err = batch(*walk_arguments(folder, str(out)))
    assert (status, err) == (125, "mbk: error: --out-dir: %s is not a folder\n" % out)
    out.unlink()
    (out / "summary.csv").mkdir(parents=True)
    status, _, err = batch(*walk_arguments(folder, str(out)))
    assert (status, err) == (125, "mbk: error: --out-dir: %s/summary.csv is not a regular file\n"
                             % out)
    (out / "summary.csv").rmdir()
    (out / ".mbk-batch").write_text("a file")
    status, _, err = batch(*walk_arguments(folder, str(out)))
    assert (status, err) == (125, "mbk: error: --out-dir: %s/.mbk-batch is not a folder\n" % out)
    (out / ".mbk-batch").unlink()
    (out / ".mbk-batch" / "w00.json").mkdir(parents=True)  # a record of the wrong kind
    status, table, err = batch(*walk_arguments(folder, str(out)))
    assert status == 1 and "Traceback" not in err
    assert summary_rows(str(out))[0]["error"] == "%s/.mbk-batch/w00.json: Is a directory" % out


def test_a_full_disk_while_writing_the_summary(tmp_path, monkeypatch, capsys):
    folder, out = walks(str(tmp_path / "in"), 1), str(tmp_path / "out")
    def full(fd):  # only the summary is synced (the records are not)
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
    monkeypatch.setattr(os, "fsync", full)
    status = mbk_batch.main(walk_arguments(folder, out))
    assert status == 124
    assert capsys.readouterr().err == "mbk: error: %s/summary.csv: No space left on device\n" % out
    left = os.listdir(out)
    assert "w00.csv" in left and "summary.csv" not in left
    assert not [f for f in left if "mbk-tmp" in f]


def test_two_runs_resuming_stale_records(tmp_path):
    folder, out = walks(str(tmp_path / "in"), 6), str(tmp_path / "out")
    batch(*walk_arguments(folder, out), check=0)
    for name in os.listdir(folder):  # every record stale
        os.utime(os.path.join(folder, name), ns=(1, 1))
    runs = [subprocess.Popen([mbk_path(), "batch"] + walk_arguments(folder, out),
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
            for _ in range(2)]
    for run in runs:
        _, err = run.communicate(timeout=120)
        assert "Traceback" not in err, err


@pytest.mark.parametrize("address", ["tls://127.0.0.1:1", "ucx://127.0.0.1:1"])
def test_schedulers_dask_cannot_reach(tmp_path, address):
    folder = walks(str(tmp_path / "in"), 1)
    status, _, err = batch(*walk_arguments(folder, str(tmp_path / "out")) +
                           ["--scheduler", address])
    assert status == 125
    assert err.startswith("mbk: error: cannot reach the Dask scheduler %s: " % address), err
    assert err.count("\n") == 1, err
