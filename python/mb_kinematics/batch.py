"""mbk batch: a whole collection of recordings (.bag, .csv, .bvh) through `mbk bag`, one job per
file, on every core of this machine or on a Dask cluster (doc/batch.md).

    mbk batch data/ --model robot.urdf --out-dir kinematics/ [--jobs N] [--bag]
    mbk batch trials/ --out-dir kinematics/ --scale 0.056444 --body-mass 68.5   # BVH: own model

Each job runs `mbk bag` on one input as a child process, so that its outputs are those of one
`mbk bag` run byte for byte, written as atomically, and a crash of one file leaves the others
going. `mbk bag --summary-json` gives each row of `summary.csv`. A finished job leaves a record
(under OUT/.mbk-batch/) of its input's size and time, the options and the tool: a later run with
the same ones skips it. The inputs: batch_inputs.py; the job and its record: batch_job.py; here
the runs, the summary and the command line.
"""
import argparse
import csv
import io
import logging
import os
import signal
import sys
import threading
import time
from concurrent.futures import FIRST_COMPLETED, ThreadPoolExecutor, wait

from mb_kinematics import _core
from mb_kinematics.batch_inputs import EXTENSIONS, SUMMARY, BatchError, find_inputs
from mb_kinematics.batch_job import (BVH_OPTIONS, COMMON_OPTIONS, STATE, failure, finished,
                                     locate_mbk_bag, plan, run_job, write_atomically)
from mb_kinematics.batch_subjects import read_subjects, subject_options

__all__ = ["run", "main", "run_job", "plan", "find_inputs", "locate_mbk_bag", "BatchError",
           "Interrupted", "EXTENSIONS", "STATE", "SUMMARY"]

COLUMNS = ["input", "output", "status", "resumed", "samples_read", "samples_written", "dropped",
           "drops", "unreadable", "estimator", "noise_level", "seconds", "error", "warnings"]
MOST_FAILURES = 100  # the exit status counts failures up to this
NO_CLUSTER_SECONDS = 60  # on Dask: how long the batch waits for a worker (or scheduler) to return
USAGE_STATUS = 125  # a wrong command line: nothing run
WRITE_STATUS = 124  # the summary (or a folder) could not be written


# --- Progress and summary ---------------------------------------------------------------------

class Progress:
    """One line on stderr: files done, samples written, time spent and left (by input bytes)."""

    def __init__(self, jobs, draw):
        self.total, self.done, self.failed, self.samples = len(jobs), 0, 0, 0
        self.bytes_total, self.bytes_done = sum(j["bytes"] for j in jobs), 0
        self.started, self.draw = time.monotonic(), draw

    def add(self, job, summary):
        self.done += 1
        self.failed += summary["status"] != "ok"
        self.samples += summary["written"]
        self.bytes_done += job["bytes"]
        if self.draw:
            sys.stderr.write("\r" + self.line() + "\033[K")
            sys.stderr.flush()

    def line(self):
        spent = time.monotonic() - self.started
        left = spent * (self.bytes_total - self.bytes_done) / max(self.bytes_done, 1)
        return ("mbk batch: %d/%d files (%d not ok), %d samples, %.0f s, about %.0f s left"
                % (self.done, self.total, self.failed, self.samples, spent, left))

    def finish(self):
        if self.draw and self.done:
            sys.stderr.write("\n")


def _row(job, summary, resumed):
    drops = "; ".join("%s: %d" % item for item in sorted(summary.get("drops", {}).items()))
    noise = summary.get("noise_level")
    return {"input": job["input"], "output": " ".join(job["outputs"]), "status": summary["status"],
            "resumed": int(resumed), "samples_read": summary["read"],
            "samples_written": summary["written"], "dropped": summary["dropped"], "drops": drops,
            "unreadable": summary["unreadable"], "estimator": summary["estimator"],
            "noise_level": "" if noise is None else repr(noise),
            "seconds": "%.3f" % summary["seconds"], "error": summary["error"],
            "warnings": " | ".join(summary.get("warnings", []))}


def write_summary(out_dir, rows):
    text = io.StringIO()
    writer = csv.DictWriter(text, COLUMNS, lineterminator="\n")
    writer.writeheader()
    writer.writerows(rows)
    write_atomically(os.path.join(out_dir, SUMMARY), text.getvalue())


def format_table(rows, seconds, most_listed=20):
    """The printed summary: files and samples by status, then each file that is not ok (the
    first `most_listed` of them; summary.csv has them all)."""
    lines = ["%-9s %7s %7s %12s %12s" % ("status", "files", "resumed", "samples in",
                                         "samples out")]
    for status in ("ok", "partial", "failed", "not run"):
        some = [r for r in rows if r["status"] == status]
        if some:
            lines.append("%-9s %7d %7d %12d %12d" % (
                status, len(some), sum(r["resumed"] for r in some),
                sum(int(r["samples_read"] or 0) for r in some),
                sum(int(r["samples_written"] or 0) for r in some)))
    warned = [r for r in rows if r.get("warnings")]
    lines.append("%d files in %.1f s%s" % (len(rows), seconds, ", %d with warnings" % len(warned)
                                           if warned else ""))
    listed = [(r["status"], r["input"], r["error"]) for r in rows
              if r["status"] in ("partial", "failed")]
    listed += [("warning", r["input"], w) for r in warned for w in r["warnings"].split(" | ")]
    for line in listed[:most_listed]:
        lines.append("%s %s: %s" % line)
    if len(listed) > most_listed:
        lines.append("... and %d more in summary.csv" % (len(listed) - most_listed))
    return "\n".join(lines) + "\n"


# --- Running ----------------------------------------------------------------------------------

class Interrupted(Exception):
    def __init__(self, signum):
        super().__init__(signal.Signals(signum).name)
        self.signum = signum


def _report_finished(waiting, report):
    """On an interruption: the jobs of `waiting` (future -> job) that finished all the same
    (ok or partial: they left their records) are reported; the others stay not run."""
    for future, job in waiting.items():
        if future.done() and not future.cancelled() and future.exception() is None:
            summary = future.result()
            if summary is not None and summary["status"] != "failed":
                report(job, summary)


def _run_local(jobs, count, report, stop):
    """Runs `jobs` on `count` concurrent child processes; report(job, summary) as each ends."""
    running = set()
    with ThreadPoolExecutor(max_workers=count) as pool:
        waiting = {pool.submit(run_job, job, running, stop.event): job for job in jobs}
        try:
            while waiting:
                done, _ = wait(list(waiting), timeout=0.2, return_when=FIRST_COMPLETED)
                stop.check()  # first: a job the signal ended is not run, not failed
                for future in done:
                    report(waiting.pop(future), future.result())
        except Interrupted:
            for future in waiting:
                future.cancel()
            for child in list(running):
                child.terminate()  # mbk bag removes its temporary files
            wait(list(waiting))
            _report_finished(waiting, report)
            raise


def _absolute(job):
    """The job with absolute paths, for a worker whose working directory is not ours."""
    absolute = dict(job, input=os.path.abspath(job["input"]),
                    outputs=[os.path.abspath(o) for o in job["outputs"]])
    absolute["output_arguments"] = [os.path.abspath(a) if a in job["outputs"] else a
                                    for a in job["output_arguments"]]
    absolute["record"] = os.path.abspath(job["record"])
    return absolute


def _cluster_gone(client):
    """Why the cluster can run nothing now ("" while it can): no worker, or no scheduler."""
    if client.status != "running":
        return "the scheduler is lost (client %s)" % client.status
    if not client.scheduler_info().get("workers"):
        return "no worker alive"
    return ""


def run_on_client(client, jobs, report, stop, patience=None):
    """Runs `jobs` on a Dask cluster (a dask.distributed.Client): one task per job, retried on
    another worker when its worker dies; a job whose task fails anyway is reported failed (but
    one that left its record, e.g. before its scheduler was lost, as it finished). When the
    cluster has had no worker or no scheduler for `patience` seconds (default
    NO_CLUSTER_SECONDS), the jobs left are reported failed, saying so."""
    patience = NO_CLUSTER_SECONDS if patience is None else patience
    futures = client.map(run_job, [_absolute(job) for job in jobs], pure=False)
    waiting = dict(zip(futures, jobs))
    gone_since = None
    try:
        while waiting:
            stop.check()
            for future in [f for f in waiting if f.done()]:
                job = waiting.pop(future)
                try:
                    summary = future.result()
                except Exception as e:  # KilledWorker, CancelledError, an import error
                    summary = finished(job) or failure(job, "%s: %s" % (type(e).__name__, e))
                report(job, summary)
            why = _cluster_gone(client) if waiting else ""
            gone_since = (time.monotonic() if gone_since is None else gone_since) if why else None
            if why and time.monotonic() - gone_since >= patience:
                if client.status == "running":
                    client.cancel(list(waiting))
                for job in waiting.values():
                    report(job, failure(job, "Dask: %s for %g s; run again to resume" %
                                        (why, patience)))
                waiting.clear()
            stop.sleep(0.2)
    except Interrupted:
        _report_finished(waiting, report)
        if client.status == "running":
            client.cancel(list(waiting))
        raise


class _Stop:
    """SIGINT and SIGTERM turned into Interrupted in the main thread; `event` is set at once (for
    the jobs' threads: none starts after it)."""

    def __init__(self):
        self.signum = None
        self.event = threading.Event()

    def __enter__(self):
        self.previous = {}
        if threading.current_thread() is threading.main_thread():  # else: no handlers of its own
            self.previous = {s: signal.signal(s, self._note)
                             for s in (signal.SIGINT, signal.SIGTERM)}
        return self

    def _note(self, signum, frame):
        self.signum = signum
        self.event.set()

    def check(self):
        if self.signum is not None:
            raise Interrupted(self.signum)

    def sleep(self, seconds):
        """Waits `seconds` or until a signal, then check()s."""
        self.event.wait(seconds)
        self.check()

    def __exit__(self, *exc):
        for s, handler in self.previous.items():
            signal.signal(s, handler)


def _bag_options(model, options):
    """mbk bag's options from run()'s keywords: max_gap=0.1 -> {"--max-gap": "0.1"}."""
    named = {"--" + name.replace("_", "-"): value for name, value in options.items()
             if value is not None and value is not False}
    unknown = sorted(set(named) - set(COMMON_OPTIONS) - set(BVH_OPTIONS))
    if unknown:
        raise BatchError("unknown option %s" % ", ".join(u[2:].replace("-", "_") for u in unknown))
    if model is not None:
        named["--model"] = model
    for name in ("--model", "--segments"):  # a worker's working directory is not ours
        if name in named:
            named[name] = os.path.abspath(named[name])
    if str(named.get("--angles", "")).endswith((".yaml", ".yml")):
        named["--angles"] = os.path.abspath(named["--angles"])
    return named


def _check_columns(named, kinds):
    """BatchError if an option adds columns to none of the outputs `kinds` (mbk bag's rule, from
    its option table), before any job runs."""
    outputs = ["--out" if kind == "bag" else "--" + kind for kind in kinds]
    try:
        _core.check_column_options(sorted(named), outputs)
    except ValueError as e:
        raise BatchError(str(e)) from None


def run(inputs, out_dir, model=None, kinds=("csv",), jobs=None, client=None, progress=False,
        mbk_bag=None, subjects=None, **options):
    """Processes the recordings `inputs` (files, folders, list files) into out_dir as
    `mbk batch` does: on `jobs` local processes (default: the cores), or on the Dask cluster of
    `client` (a dask.distributed.Client; inputs and out_dir on a path every worker sees).
    `model`: the model of .bag and .csv inputs; `options`: mbk bag's, by name with underscores
    (estimator="auto", max_gap=0.1, scale=0.056444, body_mass=68.5, ...); `subjects`: a CSV of
    per-recording scale, body_mass and sex (batch_subjects.py). Returns the summary
    rows (also in out_dir/summary.csv). Raises BatchError before running anything for a wrong
    input list or option; Interrupted (after writing the summary of what finished) when SIGINT
    or SIGTERM stops it."""
    if isinstance(inputs, (str, os.PathLike)):
        inputs = [inputs]
    inputs, out_dir = [os.fspath(i) for i in inputs], os.fspath(out_dir)
    _check_out_dir(out_dir)
    cores = len(os.sched_getaffinity(0))
    jobs = jobs or cores
    # Locally the cores are shared by the jobs; a Dask worker runs one job per thread.
    threads = 1 if client is not None else max(1, cores // jobs)
    found, chosen = find_inputs(inputs, out_dir), None
    if subjects:  # a subjects CSV among the recordings is no trajectory
        subjects = os.fspath(subjects)
        found = [f for f in found if os.path.realpath(f[0]) != os.path.realpath(subjects)]
        chosen = subject_options(read_subjects(subjects), found)
    named = _bag_options(model, options)
    _check_columns(named, kinds)
    planned = plan(found, out_dir, named, kinds, mbk_bag, threads, chosen)
    results, todo = {}, []
    for job in planned:
        earlier = finished(job)
        if earlier is not None:
            results[job["record"]] = _row(job, earlier, True)
        else:
            todo.append(job)
    bar = Progress(todo, progress)

    def report(job, summary):
        results[job["record"]] = _row(job, summary, False)
        bar.add(job, summary)

    try:
        with _Stop() as stop:
            if client is not None:
                run_on_client(client, todo, report, stop)
            else:
                _run_local(todo, jobs, report, stop)
    finally:
        bar.finish()
        not_run = lambda job: _row(job, dict(failure(job, ""), status="not run"), False)
        rows = [results.get(job["record"]) or not_run(job) for job in planned]
        write_summary(out_dir, rows)
    return rows


def _check_out_dir(out_dir):
    """BatchError unless out_dir, its summary and its records' folder are (or can be) a folder,
    a file and a folder."""
    for path, folder in ((out_dir, True), (os.path.join(out_dir, SUMMARY), False),
                         (os.path.join(out_dir, STATE), True)):
        if os.path.lexists(path) and (os.path.isdir(path) != folder or not os.path.exists(path)):
            raise BatchError("--out-dir: %s is not a %s" % (path, "folder" if folder else
                                                            "regular file"))


def exit_status(rows):
    """The number of inputs that failed or are partial (up to MOST_FAILURES); 0: all ok."""
    return min(MOST_FAILURES, sum(r["status"] in ("failed", "partial") for r in rows))


def _parser():
    p = argparse.ArgumentParser(
        prog="mbk batch", description="mbk bag over a collection of recordings (doc/batch.md)")
    p.add_argument("inputs", nargs="+", metavar="INPUT",
                   help="a .bag, .csv or .bvh file, a folder (searched recursively) or a list file")
    p.add_argument("--out-dir", required=True, metavar="DIR",
                   help="the outputs, mirroring the inputs' folders, and summary.csv")
    p.add_argument("--jobs", type=int, metavar="N",
                   help="concurrent mbk bag runs (default: the cores)")
    p.add_argument("--scheduler", metavar="tcp://HOST:PORT",
                   help="a Dask scheduler to run the jobs on instead")
    p.add_argument("--bag", action="store_true", help="write OUT.bag (--out of mbk bag)")
    p.add_argument("--csv", action="store_true", help="write OUT.csv (the default)")
    p.add_argument("--h5", action="store_true", help="write OUT.h5 (HDF5)")
    p.add_argument("--mot", action="store_true", help="write OUT.mot (OpenSim coordinates)")
    p.add_argument("--progress", action="store_true", help="the progress line even off a terminal")
    p.add_argument("--model", metavar="FILE",
                   help="the model of .bag and .csv inputs (a .bvh is its own)")
    p.add_argument("--subjects", metavar="FILE.csv",
                   help="per .bvh input (columns path or glob, scale, body_mass, sex): its "
                   "subject's options")
    for name, metavar in list(COMMON_OPTIONS.items()) + list(BVH_OPTIONS.items()):
        shown = "as mbk bag's" + (" (.bvh inputs)" if name in BVH_OPTIONS else "")
        if metavar:
            p.add_argument(name, metavar=metavar, help=shown)
        else:  # a flag
            p.add_argument(name, action="store_true", default=None, help=shown)
    return p


def _options(arguments):
    """run()'s keywords of mbk bag's options on the command line."""
    values = vars(arguments)
    return {name[2:].replace("-", "_"): values[name[2:].replace("-", "_")]
            for name in list(COMMON_OPTIONS) + list(BVH_OPTIONS)}


def _connect(address):
    """A Client of the Dask scheduler at `address`; BatchError if there is none to reach."""
    try:
        from distributed import Client
    except ImportError:
        raise BatchError("--scheduler needs Dask's distributed (Debian: python3-distributed)")
    # Dask logs a lost connection as tracebacks on stderr; mbk batch's rows and lines say it.
    logging.disable(logging.CRITICAL)
    try:
        return Client(address)
    except Exception as e:  # TimeoutError, an unknown protocol, tls:// without its certificates
        raise BatchError("cannot reach the Dask scheduler %s: %s: %s"
                         % (address, type(e).__name__, e))


def main(argv=None):
    parser = _parser()
    try:
        arguments = parser.parse_args(argv)
    except SystemExit as e:
        return 0 if e.code == 0 else USAGE_STATUS
    if arguments.jobs is not None and arguments.jobs < 1:
        sys.stderr.write("mbk: error: --jobs needs a count from 1, not %d\n" % arguments.jobs)
        return USAGE_STATUS
    kinds = [k for k in ("bag", "csv", "h5", "mot") if getattr(arguments, k)] or ["csv"]
    client, started = None, time.monotonic()
    try:
        if arguments.scheduler:
            client = _connect(arguments.scheduler)
        rows = run(arguments.inputs, arguments.out_dir, arguments.model, kinds, arguments.jobs,
                   client, arguments.progress or sys.stderr.isatty(),
                   subjects=arguments.subjects, **_options(arguments))
    except BatchError as e:
        sys.stderr.write("mbk: error: %s\n" % e)
        return USAGE_STATUS
    except OSError as e:  # the summary or a folder could not be written (a full disk)
        sys.stderr.write("mbk: error: %s: %s\n" % (e.filename or arguments.out_dir,
                                                    e.strerror or e))
        return WRITE_STATUS
    except Interrupted as e:
        sys.stderr.write("mbk batch: interrupted (%s): finished files are kept, run again to "
                         "resume\n" % e)
        return 128 + e.signum
    finally:
        if client is not None:
            client.close()
    table = format_table(rows, time.monotonic() - started)  # names as their bytes, UTF-8 or not
    sys.stdout.buffer.write(table.encode("utf-8", "surrogateescape"))
    sys.stdout.flush()
    return exit_status(rows)


if __name__ == "__main__":
    sys.exit(main())
