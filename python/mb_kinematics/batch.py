"""mbk batch: a whole collection of recordings (.bag, .csv, .bvh) through `mbk bag`, one job per
file, on every core of this machine or on a Dask cluster (doc/batch.md).

    mbk batch data/ --model robot.urdf --out-dir kinematics/ [--jobs N] [--bag]
    mbk batch trials/ --out-dir kinematics/ --scale 0.056444 --body-mass 68.5   # BVH: own model

Each job runs `mbk bag` on one input as a child process, so that its outputs are those of one
`mbk bag` run byte for byte, written as atomically, and a crash of one file leaves the others
going. `mbk bag --summary-json` gives each row of `summary.csv`. A finished job leaves a record
(under OUT/.mbk-batch/) of its input's size and time, the options and the tool: a later run with
the same ones skips it.
"""
import argparse
import csv
import hashlib
import io
import json
import os
import shutil
import signal
import subprocess
import sys
import threading
import time
from concurrent.futures import FIRST_COMPLETED, ThreadPoolExecutor, wait

EXTENSIONS = (".bag", ".csv", ".bvh")
STATE = ".mbk-batch"  # under --out-dir: the records of finished jobs
SUMMARY = "summary.csv"
COLUMNS = ["input", "output", "status", "resumed", "samples_read", "samples_written", "dropped",
           "drops", "unreadable", "estimator", "noise_level", "seconds", "error"]
# `mbk bag` options every job takes as given; those of a BVH model go to .bvh inputs only.
COMMON_OPTIONS = {"--estimator": "NAME", "--max-gap": "S", "--joint-states": "TOPIC",
                  "--joint-accelerations": "TOPIC", "--base-odometry": "TOPIC",
                  "--frame-prefix": "P", "--start-time": "S", "--threads": "N"}
BVH_OPTIONS = {"--scale": "M", "--body-mass": "KG", "--sex": "male|female",
               "--segments": "MAP.yaml"}
MOST_FAILURES = 100  # the exit status counts failures up to this
USAGE_STATUS = 125  # a wrong command line: nothing run


class BatchError(ValueError):
    """A wrong command line or input list: nothing is run."""


# --- Inputs -----------------------------------------------------------------------------------

def _walk(folder):
    """The recordings under `folder`, recursively, in sorted order."""
    found = []
    for top, dirs, files in os.walk(folder):
        dirs[:] = sorted(d for d in dirs if d != STATE)
        found += [os.path.join(top, f) for f in sorted(files) if f.endswith(EXTENSIONS)]
    return found


def _list_file(path, seen):
    """The entries of a list file: one path a line (relative to the list file's folder), blank
    lines and lines starting with # skipped."""
    base = os.path.dirname(os.path.abspath(path))
    try:
        with open(path, encoding="utf-8") as f:
            lines = [line.strip() for line in f]
    except (OSError, UnicodeDecodeError) as e:
        raise BatchError("%s: cannot read the list: %s" % (path, e))
    entries = []
    for line in lines:
        if line and not line.startswith("#"):
            entries += _expand(os.path.join(base, line), seen)
    return entries


def _expand(path, seen):
    """(input, path of its outputs relative to --out-dir without extension) for an argument."""
    if os.path.isdir(path):
        return [(f, os.path.splitext(os.path.relpath(f, path))[0]) for f in _walk(path)]
    if path.endswith(EXTENSIONS) and os.path.isfile(path):
        return [(path, os.path.splitext(os.path.basename(path))[0])]
    if os.path.isfile(path):
        real = os.path.realpath(path)
        if real in seen:
            raise BatchError("%s: a list file that lists itself" % path)
        return _list_file(path, seen | {real})
    raise BatchError("%s: no such file or folder" % path)


def find_inputs(paths, out_dir):
    """(input, relative output stem) of every recording the arguments name, in their order; the
    inputs under `out_dir` are left out. Raises BatchError for a missing path, no recording at
    all, or two inputs whose outputs would have the same name."""
    out = os.path.realpath(out_dir)
    stems, seen, found = {os.path.splitext(SUMMARY)[0]: SUMMARY}, set(), []
    for path in paths:
        for item, stem in _expand(path, frozenset()):
            real = os.path.realpath(item)
            if real == out or real.startswith(out + os.sep) or real in seen:
                continue
            key = os.path.normpath(stem)
            if key in stems:
                raise BatchError("%s and %s: both would be written as %s in --out-dir"
                                 % (stems[key], item, key))
            stems[key] = item
            seen.add(real)
            found.append((item, key))
    if not found:
        raise BatchError("no recording (%s) in %s" % (", ".join(EXTENSIONS), " ".join(paths)))
    return found


# --- One job ----------------------------------------------------------------------------------

def locate_mbk_bag():
    """The mbk_bag executable: $MBK_BAG, else beside the package's compiled part (devel or
    install space: lib/mb_kinematics/mbk_bag beside lib/python3/dist-packages/)."""
    if os.environ.get("MBK_BAG"):
        return os.environ["MBK_BAG"]
    from mb_kinematics import _core
    lib = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(_core.__file__))))
    path = os.path.join(lib, "mb_kinematics", "mbk_bag")
    if not os.path.isfile(path):
        raise RuntimeError("mbk_bag not found at %s: set MBK_BAG" % path)
    return path


def _write_atomically(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    temporary = "%s.mbk-tmp-%d-%d" % (path, os.getpid(), threading.get_ident())
    with open(temporary, "w", encoding="utf-8", newline="") as f:
        f.write(text)
        f.flush()
        os.fsync(f.fileno())
    os.replace(temporary, path)


def _file_identity(path):
    st = os.stat(path)
    return [st.st_size, st.st_mtime_ns]


def _failure(job, error):
    return {"input": job["input"], "outputs": job["outputs"], "status": "failed", "read": 0,
            "written": 0, "dropped": 0, "drops": {}, "unreadable": 0, "estimator": "",
            "noise_level": None, "seconds": 0, "error": error}


def _last_error_line(stderr):
    lines = [line for line in stderr.splitlines() if line.strip()]
    return lines[-1] if lines else ""


def _bag_command(job):
    mbk_bag = job["mbk_bag"] if os.path.isfile(job["mbk_bag"]) else locate_mbk_bag()
    command = [mbk_bag, "bag", job["input"]] + job["arguments"] + job["output_arguments"]
    command += ["--threads", str(job["threads"])]
    command += ["--summary-json", job["run_summary"]]
    setpriv = shutil.which("setpriv")
    # The job ends with the process that runs it (a Dask worker killed): its temporaries go.
    return ([setpriv, "--pdeathsig", "TERM"] if setpriv else []) + command


def run_job(job, running=None):
    """Runs `mbk bag` on one input (`job` from plan()); returns its summary (mbk bag's
    --summary-json, or a failure naming the error). A finished job (status ok or partial) leaves
    its record, so that a later run skips it. `running`: a set the child process is kept in while
    it runs (for an interruption to stop it)."""
    started = time.monotonic()
    for path in (job["record"], job["run_summary"]):
        if os.path.exists(path):
            os.remove(path)
    os.makedirs(os.path.dirname(job["record"]), exist_ok=True)
    for path in job["outputs"]:
        os.makedirs(os.path.dirname(path), exist_ok=True)
    child = subprocess.Popen(_bag_command(job), stdin=subprocess.DEVNULL,
                             stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    if running is not None:
        running.add(child)
    try:
        _, stderr = child.communicate()
    finally:
        if running is not None:
            running.discard(child)
    stderr = stderr.decode("utf-8", "replace")
    if child.returncode < 0:
        name = signal.Signals(-child.returncode).name
        return _failure(job, ("mbk bag ended by %s %s" % (name, _last_error_line(stderr))).strip())
    try:
        with open(job["run_summary"], encoding="utf-8") as f:
            summary = json.load(f)
        os.remove(job["run_summary"])
    except (OSError, ValueError):
        return _failure(job, _last_error_line(stderr) or "mbk bag wrote no summary")
    summary["input"], summary["outputs"] = job["input"], job["outputs"]
    summary["seconds"] = time.monotonic() - started
    if summary["status"] != "failed":
        record = {"key": job["key"], "summary": summary,
                  "outputs": [_file_identity(path) for path in job["outputs"]]}
        _write_atomically(job["record"], json.dumps(record, sort_keys=True))
    return summary


# --- The plan ---------------------------------------------------------------------------------

def _tool_identity(mbk_bag):
    """What changes when mbk_bag is rebuilt or upgraded: a hash of the executable."""
    digest = hashlib.sha256()
    with open(mbk_bag, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def _arguments(options, is_bvh):
    """mbk bag's options for an input but --threads (which leaves the outputs as they are)."""
    arguments = []
    names = [n for n in COMMON_OPTIONS if n != "--threads"]
    names += list(BVH_OPTIONS) if is_bvh else ["--model"]
    for name in names:
        value = options.get(name)
        if value is not None:
            arguments += [name, str(value)]
    return arguments


def _files_of(arguments):
    """The files options name (--model, --segments): their identity is part of the key."""
    return {name: _file_identity(value) if os.path.exists(value) else None
            for name, value in zip(arguments, arguments[1:]) if name in ("--model", "--segments")}


def plan(inputs, out_dir, options, kinds=("csv",), mbk_bag=None, threads=1):
    """One job per input (find_inputs' pairs): `mbk bag`'s arguments, the outputs under
    out_dir (kinds: "csv" and/or "bag"), where its record goes and the key that record must
    hold for the job to count as done. `threads`: mbk bag's --threads unless options give it."""
    mbk_bag = os.path.abspath(mbk_bag or locate_mbk_bag())
    tool = _tool_identity(mbk_bag)
    state = os.path.join(out_dir, STATE)
    jobs = []
    for path, stem in inputs:
        arguments = _arguments(options, path.endswith(".bvh"))
        outputs = [os.path.join(out_dir, stem + "." + kind) for kind in kinds]
        flags = {"bag": "--out", "csv": "--csv"}
        output_arguments = sum(([flags[k], o] for k, o in zip(kinds, outputs)), [])
        key = {"input": _file_identity(path), "arguments": arguments, "files": _files_of(arguments),
               "kinds": list(kinds), "tool": tool}
        jobs.append({"input": path, "outputs": outputs, "arguments": arguments,
                     "output_arguments": output_arguments, "mbk_bag": mbk_bag, "key": key,
                     "threads": options.get("--threads", threads),
                     "record": os.path.join(state, stem + ".json"),
                     "run_summary": os.path.join(state, stem + ".run.json"),
                     "bytes": _file_identity(path)[0]})
    return jobs


def finished(job):
    """The summary of an earlier run of this job if its record holds the same key and its
    outputs are still the files it wrote; else None."""
    try:
        with open(job["record"], encoding="utf-8") as f:
            record = json.load(f)
        if record["key"] != job["key"]:
            return None
        if [_file_identity(path) for path in job["outputs"]] != record["outputs"]:
            return None
        return record["summary"]
    except (OSError, ValueError, KeyError, TypeError):
        return None


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
            "seconds": "%.3f" % summary["seconds"], "error": summary["error"]}


def write_summary(out_dir, rows):
    text = io.StringIO()
    writer = csv.DictWriter(text, COLUMNS, lineterminator="\n")
    writer.writeheader()
    writer.writerows(rows)
    _write_atomically(os.path.join(out_dir, SUMMARY), text.getvalue())


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
    lines.append("%d files in %.1f s" % (len(rows), seconds))
    not_ok = [r for r in rows if r["status"] in ("partial", "failed")]
    for r in not_ok[:most_listed]:
        lines.append("%s %s: %s" % (r["status"], r["input"], r["error"]))
    if len(not_ok) > most_listed:
        lines.append("... and %d more in summary.csv" % (len(not_ok) - most_listed))
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
            if summary["status"] != "failed":
                report(job, summary)


def _run_local(jobs, count, report, stop):
    """Runs `jobs` on `count` concurrent child processes; report(job, summary) as each ends."""
    running = set()
    with ThreadPoolExecutor(max_workers=count) as pool:
        waiting = {pool.submit(run_job, job, running): job for job in jobs}
        try:
            while waiting:
                done, _ = wait(list(waiting), timeout=0.2, return_when=FIRST_COMPLETED)
                for future in done:
                    report(waiting.pop(future), future.result())
                stop.check()
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
    for name in ("record", "run_summary"):
        absolute[name] = os.path.abspath(job[name])
    return absolute


def run_on_client(client, jobs, report, stop):
    """Runs `jobs` on a Dask cluster (a dask.distributed.Client): one task per job, retried on
    another worker when its worker dies; a job whose task fails anyway is reported failed."""
    from distributed import as_completed
    futures = client.map(run_job, [_absolute(job) for job in jobs], pure=False)
    waiting = dict(zip(futures, jobs))
    try:
        for future in as_completed(futures):
            stop.check()
            job = waiting.pop(future)
            try:
                summary = future.result()
            except Exception as e:  # KilledWorker, a worker that cannot import the package
                summary = _failure(job, "%s: %s" % (type(e).__name__, e))
            report(job, summary)
    except Interrupted:
        _report_finished(waiting, report)
        client.cancel(list(waiting))
        raise


class _Stop:
    """SIGINT and SIGTERM turned into Interrupted in the main thread."""

    def __init__(self):
        self.signum = None

    def __enter__(self):
        self.previous = {}
        if threading.current_thread() is threading.main_thread():  # else: no handlers of its own
            self.previous = {s: signal.signal(s, self._note)
                             for s in (signal.SIGINT, signal.SIGTERM)}
        return self

    def _note(self, signum, frame):
        self.signum = signum

    def check(self):
        if self.signum is not None:
            raise Interrupted(self.signum)

    def __exit__(self, *exc):
        for s, handler in self.previous.items():
            signal.signal(s, handler)


def _bag_options(model, options):
    """mbk bag's options from run()'s keywords: max_gap=0.1 -> {"--max-gap": "0.1"}."""
    named = {"--" + name.replace("_", "-"): value for name, value in options.items()
             if value is not None}
    unknown = sorted(set(named) - set(COMMON_OPTIONS) - set(BVH_OPTIONS))
    if unknown:
        raise BatchError("unknown option %s" % ", ".join(u[2:].replace("-", "_") for u in unknown))
    if model is not None:
        named["--model"] = model
    for name in ("--model", "--segments"):  # a worker's working directory is not ours
        if name in named:
            named[name] = os.path.abspath(named[name])
    return named


def run(inputs, out_dir, model=None, kinds=("csv",), jobs=None, client=None, progress=False,
        mbk_bag=None, **options):
    """Processes the recordings `inputs` (files, folders, list files) into out_dir as
    `mbk batch` does: on `jobs` local processes (default: the cores), or on the Dask cluster of
    `client` (a dask.distributed.Client; inputs and out_dir on a path every worker sees).
    `model`: the model of .bag and .csv inputs; `options`: mbk bag's, by name with underscores
    (estimator="auto", max_gap=0.1, scale=0.056444, body_mass=68.5, ...). Returns the summary
    rows (also in out_dir/summary.csv). Raises BatchError before running anything for a wrong
    input list or option; Interrupted (after writing the summary of what finished) when SIGINT
    or SIGTERM stops it."""
    if isinstance(inputs, (str, os.PathLike)):
        inputs = [inputs]
    inputs, out_dir = [os.fspath(i) for i in inputs], os.fspath(out_dir)
    cores = len(os.sched_getaffinity(0))
    jobs = jobs or cores
    # Locally the cores are shared by the jobs; a Dask worker runs one job per thread.
    threads = 1 if client is not None else max(1, cores // jobs)
    planned = plan(find_inputs(inputs, out_dir), out_dir, _bag_options(model, options), kinds,
                   mbk_bag, threads)
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
        not_run = lambda job: _row(job, dict(_failure(job, ""), status="not run"), False)
        rows = [results.get(job["record"]) or not_run(job) for job in planned]
        write_summary(out_dir, rows)
    return rows


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
    p.add_argument("--progress", action="store_true", help="the progress line even off a terminal")
    p.add_argument("--model", metavar="FILE",
                   help="the model of .bag and .csv inputs (a .bvh is its own)")
    for name, metavar in list(COMMON_OPTIONS.items()) + list(BVH_OPTIONS.items()):
        p.add_argument(name, metavar=metavar,
                       help="as mbk bag's" + (" (.bvh inputs)" if name in BVH_OPTIONS else ""))
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
    try:
        return Client(address)
    except (OSError, ValueError) as e:  # TimeoutError is an OSError
        raise BatchError("cannot reach the Dask scheduler %s: %s" % (address, e))


def main(argv=None):
    parser = _parser()
    try:
        arguments = parser.parse_args(argv)
    except SystemExit as e:
        return 0 if e.code == 0 else USAGE_STATUS
    if arguments.jobs is not None and arguments.jobs < 1:
        sys.stderr.write("mbk: error: --jobs needs a count from 1, not %d\n" % arguments.jobs)
        return USAGE_STATUS
    kinds = [k for k in ("bag", "csv") if getattr(arguments, k)] or ["csv"]
    client, started = None, time.monotonic()
    try:
        if arguments.scheduler:
            client = _connect(arguments.scheduler)
        rows = run(arguments.inputs, arguments.out_dir, arguments.model, kinds, arguments.jobs,
                   client, arguments.progress or sys.stderr.isatty(), **_options(arguments))
    except BatchError as e:
        sys.stderr.write("mbk: error: %s\n" % e)
        return USAGE_STATUS
    except Interrupted as e:
        sys.stderr.write("mbk batch: interrupted (%s): finished files are kept, run again to "
                         "resume\n" % e)
        return 128 + e.signum
    finally:
        if client is not None:
            client.close()
    sys.stdout.write(format_table(rows, time.monotonic() - started))
    return exit_status(rows)


if __name__ == "__main__":
    sys.exit(main())
