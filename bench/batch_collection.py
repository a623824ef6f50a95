#!/usr/bin/env python3
"""mbk batch's speed (doc/speed.md#a-collection-mbk-batch): a collection of --files BVH walks
(the CMU trials of test/mocap, their first --frames frames, copied in turn) through a shell loop
of `mbk bag`, two such loops at once (each over half the files), `mbk batch --jobs 1`, `--jobs 2`
and `--jobs 1 --threads 1` (one core), and a Dask LocalCluster of two worker processes (one
thread each), in the same run, each run's outputs checked against the loop's and removed; files/s,
samples/s, and the speed-ups. Then the
per-file overhead: the start of mbk_bag (`mbk bag --help`), and an `mbk bag` run on a walk of 10
frames (start, model, reading, writing), the least of --repeats runs. Prints a markdown table
(CPU s: the CPU time of the processes a run started, which the machine's other load leaves
about as it is; cores busy: CPU s / s), the load average before and after, and the speed-ups.
Not a test: the figures depend on the machine's load.

  source devel/setup.bash; cd /tmp; /usr/bin/python3 .../bench/batch_collection.py [--files 200]
  (run outside the repository's root, which would shadow the package)
"""
import argparse
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time

from mb_kinematics import batch

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
TRIALS = ["131_01.bvh", "131_03.bvh"]
SCALE, MASS = "0.056444", "68.5"


def mbk():
    return os.path.join(os.path.dirname(batch.locate_mbk_bag()), "mbk")


def trimmed(name, path, frames):
    with open(os.path.join(ROOT, "test", "mocap", name)) as f:
        lines = f.read().split("\n")
    motion = lines.index("MOTION")
    lines[motion + 1] = "Frames: %d" % frames
    with open(path, "w") as f:
        f.write("\n".join(lines[:motion + 3 + frames]) + "\n")


def collection(folder, files, frames):
    """`files` walks in ten subfolders."""
    for i in range(files):
        sub = os.path.join(folder, "session%d" % (i % 10))
        os.makedirs(sub, exist_ok=True)
        trimmed(TRIALS[i % 2], os.path.join(sub, "walk%03d.bvh" % i), frames)


def timed(f):
    start = time.perf_counter()
    f()
    return time.perf_counter() - start


def children_cpu():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def timed_with_cpu(f):
    """Wall seconds and the CPU seconds of the child processes (and theirs) it waited for."""
    cpu = children_cpu()
    return timed(f), children_cpu() - cpu


def shell_loop(folder, out, parts=1, threads=()):
    """A shell loop of `mbk bag` over the collection; `parts` loops at once, each over every
    parts-th file (the most two independent processes give, without mbk batch)."""
    script = ('for f in $(find "$1" -name "*.bvh" | sort | awk "NR %% $4 == $5"); do r=${f#$1/}; '
              'mkdir -p "$2/$(dirname "$r")"; "$3" bag "$f" --scale %s --body-mass %s '
              '--csv "$2/${r%%.bvh}.csv" %s 2>/dev/null; done' % (SCALE, MASS, " ".join(threads)))
    loops = [subprocess.Popen(["bash", "-c", script, "loop", folder, out, mbk(), str(parts),
                               str(k)]) for k in range(parts)]
    assert all(loop.wait() == 0 for loop in loops)


ONE_CORE = "mbk batch --jobs 1 --threads 1"
TWO_LOOPS = "two shell loops at once (--threads 1)"
DASK = "Dask LocalCluster, 2 workers"


def mbk_batch(folder, out, jobs, extra=()):
    done = subprocess.run([mbk(), "batch", folder, "--out-dir", out, "--jobs", str(jobs),
                           "--scale", SCALE, "--body-mass", MASS, *extra], capture_output=True)
    assert done.returncode == 0, done.stderr


def dask_run(folder, out, client):
    rows = batch.run([folder], out, client=client, scale=SCALE, body_mass=MASS)
    assert all(r["status"] == "ok" for r in rows)


def least(command, repeats):
    return min(timed(lambda: subprocess.run(command, capture_output=True))
               for _ in range(repeats))


def overhead(work, repeats):
    tiny = os.path.join(work, "tiny.bvh")
    trimmed(TRIALS[0], tiny, 10)
    start = least([mbk(), "bag", "--help"], repeats)
    run = least([mbk(), "bag", tiny, "--scale", SCALE, "--body-mass", MASS, "--csv",
                 os.path.join(work, "tiny.csv")], repeats)
    python = least([sys.executable, "-c", "import mb_kinematics.batch"], repeats)
    return start, run, python


def same_outputs(a, b):
    for top, dirs, files in os.walk(a):
        dirs[:] = [d for d in dirs if d != batch.STATE]
        for name in files:
            if name == batch.SUMMARY:
                continue
            path = os.path.join(top, name)
            with open(path, "rb") as f, open(os.path.join(b, os.path.relpath(path, a)), "rb") as g:
                if f.read() != g.read():
                    return False
    return True


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--files", type=int, default=200)
    p.add_argument("--frames", type=int, default=240, help="per walk (120 Hz)")
    p.add_argument("--repeats", type=int, default=5)
    args = p.parse_args()
    from distributed import Client, LocalCluster
    load = os.getloadavg()
    work = tempfile.mkdtemp(prefix="mbk_batch_bench_")
    try:
        folder = os.path.join(work, "walks")
        collection(folder, args.files, args.frames)
        samples = args.files * args.frames
        seconds, cpu = {}, {}
        reference = os.path.join(work, "loop")
        seconds["shell loop of mbk bag"], cpu["shell loop of mbk bag"] = timed_with_cpu(
            lambda: shell_loop(folder, reference))

        def measure(name, run):
            """Times run(out), checks its outputs against the loop's and removes them (kept, the
            runs' gigabytes would leave the later runs writing beside the earlier ones' writeback)."""
            out = os.path.join(work, "out")
            subprocess.run(["sync"], check=True)
            seconds[name], cpu[name] = timed_with_cpu(lambda: run(out))
            assert same_outputs(reference, out), name
            shutil.rmtree(out)

        measure(TWO_LOOPS, lambda out: shell_loop(folder, out, 2, ("--threads", "1")))
        for jobs in (1, 2):
            measure("mbk batch --jobs %d" % jobs, lambda out: mbk_batch(folder, out, jobs))
        # One core: the speed-up of the jobs alone, without mbk bag's own threads.
        measure(ONE_CORE, lambda out: mbk_batch(folder, out, 1, ("--threads", "1")))
        started = time.perf_counter()
        cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                               host="127.0.0.1", dashboard_address=None)
        with Client(cluster) as client:
            cluster_start = time.perf_counter() - started
            measure(DASK, lambda out: dask_run(folder, out, client))
        cluster.close()
        cpu.pop(DASK)  # its workers' processes are not this one's children
        start, run, python = overhead(work, args.repeats)
    finally:
        shutil.rmtree(work)
    print("%d walks of %d frames (%d samples), %d cores; load average %.2f before, %.2f after\n"
          % (args.files, args.frames, samples, len(os.sched_getaffinity(0)), load[0],
             os.getloadavg()[0]))
    print("| run | s | files/s | samples/s | vs --jobs 1 | CPU s | cores busy |")
    print("|---|---|---|---|---|---|---|")
    one = seconds["mbk batch --jobs 1"]
    for name, s in seconds.items():
        print("| %s | %.1f | %.1f | %.0f | %.2fx | %s | %s |" % (
            name, s, args.files / s, samples / s, one / s,
            "%.1f" % cpu[name] if name in cpu else "(workers')",
            "%.2f" % (cpu[name] / s) if name in cpu else ""))
    two = seconds["mbk batch --jobs 2"]
    busy, cores = cpu["mbk batch --jobs 1"] / one, len(os.sched_getaffinity(0))
    print("\n--jobs 2 / --jobs 1: %.2fx the files/s (wanted: at least 1.8x)." % (one / two))
    print("--jobs 2 / one job on one core (--threads 1): %.2fx the files/s" % (
        seconds[ONE_CORE] / two))
    if busy >= 1:
        print("One job keeps %.2f cores busy (mbk bag's --threads: the cores), so two on %d cores "
              "give at most %.2fx (%d / %.2f) at the same CPU s per file" % (
                  busy, cores, cores / busy, cores, busy))
    else:
        print("One job kept %.2f cores busy: the machine's other load took the rest, so the "
              "speed-ups say little (run it again when `uptime` shows a load under 1)" % busy)
    print("--jobs 2 / two shell loops at once: %.2f of their time" % (two / seconds[TWO_LOOPS]))
    dask = seconds[DASK]
    print("Dask / --jobs 2: %.2f (the cluster's start, %.1f s, not counted)" % (dask / two,
                                                                                 cluster_start))
    print("per file: mbk bag's start (--help) %.3f s; a 10-frame walk %.3f s (start, model, "
          "read, write); the batch's Python start %.3f s once; the collection's mean %.3f s "
          "per file with one job" % (start, run, python, one / args.files))
    print("outputs: every run's byte for byte the loop's")


if __name__ == "__main__":
    main()
