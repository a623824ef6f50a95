"""mbk batch's job (doc/batch.md): `mbk bag` on one input as a child process, here or on a Dask
worker, and the record a finished job leaves so that a later run with the same input, options
and tool skips it."""
import glob
import hashlib
import json
import os
import shutil
import signal
import subprocess
import threading
import time

from mb_kinematics import _core

STATE = ".mbk-batch"  # under --out-dir: the records of finished jobs
# `mbk bag` options (name -> its value in the usage) from its one table (tools/bag_cli.cc): those
# every job takes as given, and a BVH model's, which go to .bvh inputs only.
COMMON_OPTIONS = {name: value for name, value, use in _core.bag_options() if use == "every job"}
BVH_OPTIONS = {name: value for name, value, use in _core.bag_options() if use == "bvh jobs"}


def locate_mbk_bag():
    """The mbk_bag executable: $MBK_BAG, else beside the package's compiled part (devel or
    install space: lib/mb_kinematics/mbk_bag beside lib/python3/dist-packages/)."""
    if os.environ.get("MBK_BAG"):
        return os.environ["MBK_BAG"]
    lib = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(_core.__file__))))
    path = os.path.join(lib, "mb_kinematics", "mbk_bag")
    if not os.path.isfile(path):
        raise RuntimeError("mbk_bag not found at %s: set MBK_BAG" % path)
    return path


def write_atomically(path, text, durable=True):
    """`text` to `path` under a temporary name, renamed into place when whole; `durable`: on the
    disk (fsync) before the rename."""
    os.makedirs(os.path.dirname(path), exist_ok=True)
    temporary = "%s.mbk-tmp-%d-%d" % (path, os.getpid(), threading.get_ident())
    try:  # names not in UTF-8 (surrogate escapes) are written as the bytes they were
        with open(temporary, "w", encoding="utf-8", errors="surrogateescape", newline="") as f:
            f.write(text)
            if durable:
                f.flush()
                os.fsync(f.fileno())
        os.replace(temporary, path)
    except BaseException as e:  # a full disk, a folder at `path`: no temporary left
        if os.path.lexists(temporary):
            os.remove(temporary)
        if isinstance(e, OSError) and not e.filename:
            e.filename = path
        raise


def _file_identity(path):
    st = os.stat(path)
    return [st.st_size, st.st_mtime_ns]


WARNING = "mbk: warning: "  # how mbk bag starts each warning line on stderr


def failure(job, error, warnings=()):
    return {"input": job["input"], "outputs": job["outputs"], "status": "failed", "read": 0,
            "written": 0, "dropped": 0, "drops": {}, "unreadable": 0, "estimator": "",
            "noise_level": None, "seconds": 0, "error": error, "warnings": list(warnings)}


def _warnings(stderr):
    """The warnings mbk bag printed, each without its "mbk: warning: "."""
    return [line[len(WARNING):] for line in stderr.splitlines() if line.startswith(WARNING)]


def _last_error_line(stderr):
    lines = [line for line in stderr.splitlines() if line.strip()]
    return lines[-1] if lines else ""


def _bag_command(job):
    mbk_bag = job["mbk_bag"] if os.path.isfile(job["mbk_bag"]) else locate_mbk_bag()
    command = [mbk_bag, "bag", job["input"]] + job["arguments"] + job["output_arguments"]
    command += ["--threads", str(job["threads"])]
    # The summary on the pipe it is read from: no file to write, rename, read and remove per job.
    command += ["--summary-json", "/dev/stdout"]
    setpriv = shutil.which("setpriv")
    # The job ends with the process that runs it (a Dask worker killed): its temporaries go.
    return ([setpriv, "--pdeathsig", "TERM"] if setpriv else []) + command


def run_job(job, running=None, stop=None):
    """Runs `mbk bag` on one input (`job` from plan()); returns its summary (mbk bag's
    --summary-json, or a failure naming the error). A finished job (status ok or partial) leaves
    its record, so that a later run skips it. `running`: a set the child process is kept in while
    it runs (for an interruption to stop it); `stop`: a threading.Event set on an interruption,
    after which no job starts (None is returned) and a child just started is ended."""
    try:
        return _run_job(job, running, stop)
    except OSError as e:  # the records' folder or an output's folder of the wrong kind, a full disk
        return failure(job, "%s: %s" % (e.filename or job["record"], e.strerror or e))


def _run_job(job, running, stop):
    started = time.monotonic()
    if stop is not None and stop.is_set():
        return None
    try:
        if os.path.lexists(job["record"]):
            os.remove(job["record"])
    except FileNotFoundError:  # another run on this --out-dir removed it first
        pass
    os.makedirs(os.path.dirname(job["record"]), exist_ok=True)
    for path in job["outputs"]:
        os.makedirs(os.path.dirname(path), exist_ok=True)
    child = subprocess.Popen(_bag_command(job), stdin=subprocess.DEVNULL,
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    if running is not None:
        running.add(child)
    if stop is not None and stop.is_set():  # the interruption's loop over `running` came first
        child.terminate()
    try:
        stdout, stderr = child.communicate()
    finally:
        if running is not None:
            running.discard(child)
    stderr = stderr.decode("utf-8", "replace")
    warnings = _warnings(stderr)
    if child.returncode < 0:
        name = signal.Signals(-child.returncode).name
        return failure(job, ("mbk bag ended by %s %s" % (name, _last_error_line(stderr))).strip(),
                       warnings)
    try:
        summary = json.loads(stdout.decode("utf-8", "replace"))
    except ValueError:
        return failure(job, _last_error_line(stderr) or "mbk bag wrote no summary", warnings)
    summary["input"], summary["outputs"] = job["input"], job["outputs"]
    summary["warnings"] = warnings
    summary["seconds"] = time.monotonic() - started
    if summary["status"] != "failed":
        record = {"key": job["key"], "summary": summary,
                  "outputs": [_file_identity(path) for path in job["outputs"]]}
        # Not synced: a record a power cut loses only makes its job run again, and the outputs'
        # sizes and times it holds catch outputs a power cut cut short (mbk bag does not sync
        # them either). The sync was an idle wait per file, longer while the disk writes back.
        write_atomically(job["record"], json.dumps(record, sort_keys=True), durable=False)
    return summary


def _tool_identity(mbk_bag):
    """What changes when mbk_bag is rebuilt or upgraded: a hash of the executable and of the
    package's libraries beside it (lib/libmbk_*.so above lib/mb_kinematics/mbk_bag), which hold
    its code: a rebuilt library changes the outputs as a rebuilt executable does."""
    lib = os.path.dirname(os.path.dirname(os.path.abspath(mbk_bag)))
    digest = hashlib.sha256()
    for path in [mbk_bag] + sorted(glob.glob(os.path.join(lib, "libmbk_*.so*"))):
        digest.update(os.path.basename(path).encode() + b"\0")
        with open(path, "rb") as f:
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
        if COMMON_OPTIONS.get(name) == "":  # a flag
            arguments += [name] if value else []
        elif value is not None:
            arguments += [name, str(value)]
    return arguments


def _files_of(arguments):
    """The files options name (--model, --segments, --angles ORDERS.yaml): their identity is
    part of the key."""
    return {name: _file_identity(value) if os.path.exists(value) else None
            for name, value in zip(arguments, arguments[1:])
            if name in ("--model", "--segments", "--angles")}


def plan(inputs, out_dir, options, kinds=("csv",), mbk_bag=None, threads=1, subjects=None):
    """One job per input (find_inputs' pairs): `mbk bag`'s arguments, the outputs under
    out_dir (kinds: "csv", "bag", "h5", "mot"), where its record goes and the key that record
    must hold for the job to count as done. `threads`: mbk bag's --threads unless options give
    it; `subjects`: input -> options that replace those of `options` for it (batch_subjects.py)."""
    mbk_bag = os.path.abspath(mbk_bag or locate_mbk_bag())
    tool = _tool_identity(mbk_bag)
    state = os.path.join(out_dir, STATE)
    jobs = []
    for path, stem in inputs:
        arguments = _arguments(dict(options, **(subjects or {}).get(path, {})),
                               path.endswith(".bvh"))
        outputs = [os.path.join(out_dir, stem + "." + kind) for kind in kinds]
        flags = {"bag": "--out", "csv": "--csv", "h5": "--h5", "mot": "--mot"}
        output_arguments = sum(([flags[k], o] for k, o in zip(kinds, outputs)), [])
        key = {"input": _file_identity(path), "arguments": arguments, "files": _files_of(arguments),
               "kinds": list(kinds), "tool": tool}
        jobs.append({"input": path, "outputs": outputs, "arguments": arguments,
                     "output_arguments": output_arguments, "mbk_bag": mbk_bag, "key": key,
                     "threads": options.get("--threads", threads),
                     "record": os.path.join(state, stem + ".json"),
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
