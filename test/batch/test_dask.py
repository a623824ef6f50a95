"""mbk batch on a Dask cluster (doc/batch.md): a LocalCluster of two worker processes on
loopback, through the Python call with a Client and through `mbk batch --scheduler`; a worker
killed while it runs a job: the job is retried (or reported), never lost or counted twice; the
outputs byte for byte those of direct `mbk bag` runs."""
import os
import shutil
import signal
import threading
import time

import psutil
import pytest
from distributed import Client, LocalCluster

from conftest import (CMU_MASS, CMU_SCALE, PANDA, batch, batch_arguments, output_files,
                      summary_rows)
from mb_kinematics import batch as mbk_batch


@pytest.fixture(scope="module")
def client():
    cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                           dashboard_address=None)
    with Client(cluster) as c:
        yield c
    cluster.close()


def walk_rows(walks, out, client):
    return mbk_batch.run([walks], out, client=client, scale=CMU_SCALE, body_mass=CMU_MASS)


def test_python_call_with_a_client(walk_template, client, tmp_path):
    walks, expected = walk_template
    out = str(tmp_path / "out")
    rows = walk_rows(walks, out, client)
    assert [r["status"] for r in rows] == ["ok"] * 6
    assert output_files(out) == expected
    assert summary_rows(out) == [{k: str(v) for k, v in r.items()} for r in rows]
    again = walk_rows(walks, out, client)  # resumed, as locally
    assert [r["resumed"] for r in again] == [1] * 6


def test_scheduler_option_and_the_damaged_bag(collection, direct_runs, client, tmp_path):
    """Paths relative to mbk batch's working directory, which the workers do not share."""
    address, here = client.scheduler.address, str(tmp_path)
    arguments = batch_arguments(os.path.relpath(collection, here), "out", "--scheduler", address)
    status, table, _ = batch(*arguments, cwd=here)
    assert status == 1 and "arm/damaged.bag" in table
    assert output_files(str(tmp_path / "out")) == output_files(direct_runs[0])
    status, table, _ = batch(*arguments, cwd=here)
    rows = summary_rows(str(tmp_path / "out"))
    assert status == 1 and [r["resumed"] for r in rows].count("1") == len(rows) - 1


def mbk_bag_children(pid):
    return [c for c in psutil.Process(pid).children(recursive=True)
            if "mbk_bag" in " ".join(c.cmdline())]


def kill_a_worker_in_a_job(client, killed):
    """Kills (SIGKILL) the first worker process seen running mbk bag."""
    pids = client.run(os.getpid).values()
    deadline = time.monotonic() + 30
    while time.monotonic() < deadline:
        for pid in pids:
            try:
                if mbk_bag_children(pid):
                    os.kill(pid, signal.SIGKILL)
                    killed.append(pid)
                    return
            except psutil.NoSuchProcess:
                pass
        time.sleep(0.01)


def test_worker_killed_mid_run(walk_template, client, tmp_path):
    walks, expected = walk_template
    out = str(tmp_path / "out")
    killed = []
    killer = threading.Thread(target=kill_a_worker_in_a_job, args=(client, killed))
    killer.start()
    rows = walk_rows(walks, out, client)
    killer.join()
    assert len(killed) == 1
    assert [os.path.relpath(r["input"], walks) for r in rows] == sorted(
        os.path.relpath(os.path.join(top, f), walks)
        for top, _, files in os.walk(walks) for f in files)
    for row in rows:  # retried on the other worker, or reported as failed
        assert row["status"] == "ok" or "KilledWorker" in row["error"], row
    assert [r["status"] for r in rows].count("ok") >= 5
    ok = {os.path.splitext(os.path.relpath(r["input"], walks))[0] for r in rows
          if r["status"] == "ok"}
    outputs = output_files(out)
    assert {name: data for name, data in outputs.items()
            if name.split(".")[0] in ok} == {name: data for name, data in expected.items()
                                             if name.split(".")[0] in ok}
    time.sleep(0.3)  # the killed worker's mbk bag ended with it: no temporary file left
    assert not [name for name in os.listdir(out) if "mbk-tmp" in name]


def test_no_scheduler_there(collection, tmp_path):
    import socket
    with socket.socket() as s:  # a port nothing listens on
        s.bind(("127.0.0.1", 0))
        address = "tcp://127.0.0.1:%d" % s.getsockname()[1]
    os.environ["DASK_DISTRIBUTED__COMM__TIMEOUTS__CONNECT"] = "0.3s"
    try:
        status, out, err = batch(collection, "--out-dir", str(tmp_path / "o"), "--scheduler",
                                 address)
    finally:
        del os.environ["DASK_DISTRIBUTED__COMM__TIMEOUTS__CONNECT"]
    assert (status, out) == (125, "")
    assert err.startswith("mbk: error: cannot reach the Dask scheduler %s: " % address), err
    assert len(err.splitlines()) == 1
