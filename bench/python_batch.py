#!/usr/bin/env python3
"""The Python module's speed (doc/speed.md#python): Model.kinematics on N = 1e5 states of
config/human_body.urdf and test/robots/panda.urdf (a 7-joint arm), full outputs (the default
with accelerations) and poses only, one and two threads, into out= arrays allocated before
(as batch_benchmark's C++ rows, run in the same invocation); a Python loop
over PyKDL's chain solvers (panda: the hand's pose and velocity, then every body's) and over dartpy (every body's
pose, velocities and accelerations) on 1000 states; the peak memory of a fresh call (a child
process: its peak RSS during the call, VmHWM reset just before it, above its RSS then) against the bytes of the arrays
asked for; then the human model's writing in place, fresh arrays and chunks (chunk_rows, alone
with --in-place-only). Prints markdown tables. Not a test: the figures depend on the machine's
load.

  source devel/setup.bash; /usr/bin/python3 bench/python_batch.py [--samples N] [--in-place-only]
  (run outside the repository's root, which would shadow the package: e.g. cd /tmp first)
"""
import argparse
import json
import os
import subprocess
import sys
import threading
import time

import numpy as np

import mb_kinematics

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
MODELS = {"human": "config/human_body.urdf", "panda": "test/robots/panda.urdf"}
POSE = ["rotation", "origin"]
# batch_benchmark's output sets: full, the 13 outputs given by default with accelerations; all,
# every output but the partial velocities (full and the opt-in segment frames and joint motion).
FULL = [k for k in mb_kinematics.OUTPUTS if k not in mb_kinematics.OPT_IN]
ALL = [k for k in mb_kinematics.OUTPUTS if not k.startswith("partial_")]


def states(model, n, seed=1):
    rng = np.random.default_rng(seed)
    return (rng.uniform(-0.5, 0.5, (n, model.nq)), rng.uniform(-0.5, 0.5, (n, model.nv)),
            rng.uniform(-0.5, 0.5, (n, model.nv)))


def timings(f, repeats=3):
    """The times (s) of `repeats` runs of f."""
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        f()
        times.append(time.perf_counter() - start)
    return times


def best(f, repeats=3):
    return min(timings(f, repeats))


def batch_benchmark():
    """The workspace's batch_benchmark (devel/setup.bash sourced)."""
    for prefix in os.environ.get("CMAKE_PREFIX_PATH", "").split(":"):
        path = os.path.join(prefix, "lib", "mb_kinematics", "batch_benchmark")
        if prefix and os.path.isfile(path):
            return path
    raise RuntimeError("batch_benchmark not found: build it and source devel/setup.bash")


def cpp_rows(pattern=".", repeats=1):
    """batch_benchmark's rows matching `pattern` (seconds per run of 1e5 samples), from the
    workspace: per row the times of `repeats` repetitions."""
    out = subprocess.run([batch_benchmark(), "--benchmark_format=json",
                          "--benchmark_min_time=0.5", "--benchmark_filter=" + pattern,
                          "--benchmark_repetitions=%d" % repeats],
                         capture_output=True, text=True, check=True).stdout
    rows = {}
    for b in json.loads(out)["benchmarks"]:
        if b.get("run_type", "iteration") == "iteration":
            rows.setdefault(b["run_name"].replace("/real_time", ""), []).append(
                b["real_time"] / 1e3)
    return rows


def peak_memory(name, outputs, n):
    """A child process: peak RSS during one fresh call above the RSS before it, and the bytes
    of the arrays it returns."""
    code = """
import sys, numpy as np, mb_kinematics
m = mb_kinematics.load(sys.argv[1]); n = int(sys.argv[2]); outputs = sys.argv[3].split(",")
rng = np.random.default_rng(1)
q, v, a = (rng.uniform(-0.5, 0.5, (n, k)) for k in (m.nq, m.nv, m.nv))
m.kinematics(q[:10], v[:10], a[:10], outputs=outputs)
def status(key):
    line = next(l for l in open("/proc/self/status") if l.startswith(key))
    return int(line.split()[1]) * 1024
open("/proc/self/clear_refs", "w").write("5")  # the peak RSS from here on
before = status("VmRSS:")
out = m.kinematics(q, v, a, outputs=outputs, threads=2)
print(status("VmHWM:") - before, sum(x.nbytes for x in out.values()))
"""
    done = subprocess.run([sys.executable, "-c", code, os.path.join(ROOT, MODELS[name]), str(n),
                           ",".join(outputs)], capture_output=True, text=True, check=True,
                          cwd="/tmp")
    used, asked = map(int, done.stdout.split())
    return used, asked


def pykdl_loop(model, q, v, tips):
    """Per sample, PyKDL's position and velocity solvers on a chain to each tip's mass center."""
    import PyKDL
    sys.path.insert(0, os.path.join(ROOT, "test", "python"))
    from test_peers import kdl_chain
    solvers = []
    for tip in tips:
        chain, names = kdl_chain(PyKDL, os.path.join(ROOT, MODELS["panda"]), tip,
                                 model.mass_centers[model.body_index(tip) - 1])
        solvers.append(([model.coordinate_names.index(n) for n in names],
                        PyKDL.ChainFkSolverPos_recursive(chain),
                        PyKDL.ChainFkSolverVel_recursive(chain),
                        PyKDL.JntArray(len(names)), PyKDL.JntArray(len(names))))
    frame, frame_vel = PyKDL.Frame(), PyKDL.FrameVel()

    def run():
        for s in range(len(q)):
            for columns, pos, vel, qq, vv in solvers:
                for i, c in enumerate(columns):
                    qq[i], vv[i] = q[s, c], v[s, c]
                pos.JntToCart(qq, frame)
                vel.JntToCart(PyKDL.JntArrayVel(qq, vv), frame_vel)
    return best(run, 1) / len(q)


def dartpy_loop(name, model, q, v, a):
    import dartpy
    loader = dartpy.utils.DartLoader()
    options = dartpy.utils.DartLoaderOptions()
    options.mDefaultRootJointType = dartpy.utils.DartLoaderRootJointType.FIXED
    loader.setOptions(options)
    skeleton = loader.parseSkeleton(os.path.join(ROOT, MODELS[name]))
    dofs = [model.coordinate_names.index(skeleton.getDof(i).getName())
            for i in range(skeleton.getNumDofs())]
    nodes = [skeleton.getBodyNode(i) for i in range(skeleton.getNumBodyNodes())]

    def run():
        for s in range(len(q)):
            skeleton.setPositions(q[s, dofs])
            skeleton.setVelocities(v[s, dofs])
            skeleton.setAccelerations(a[s, dofs])
            for node in nodes:
                node.getTransform(), node.getCOM(), node.getAngularVelocity()
                node.getAngularAcceleration(), node.getCOMLinearVelocity()
                node.getCOMLinearAcceleration()
    return best(run, 1) / len(q)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--samples", type=int, default=100000)
    parser.add_argument("--in-place-only", action="store_true",
                        help="only the last table (out=, fresh arrays, chunks)")
    arguments = parser.parse_args()
    n = arguments.samples
    if arguments.in_place_only:
        return chunk_rows(n)
    cpp = {k: min(t) for k, t in cpp_rows("batch/").items()}
    print("| model | outputs | threads | Python call, out= (ms) | C++ batch_kinematics (ms) | "
          "Python / C++ | ns per body and sample |")
    print("|---|---|---:|---:|---:|---:|---:|")
    for name, path in MODELS.items():
        model = mb_kinematics.load(os.path.join(ROOT, path))
        q, v, a = states(model, n)
        for kind, names in (("full", FULL), ("pose", POSE)):
            fresh0 = model.kinematics(q[:1], v[:1], a[:1], outputs=names)
            # Touched before, as batch_benchmark's arrays (np.zeros would leave the pages to the
            # calls timed: the first then takes seconds here, and the next ones stay slower).
            out = {k: np.ones((n,) + x.shape[1:]) for k, x in fresh0.items()}
            for threads in (1, 2):
                call = best(lambda: model.kinematics(q, v, a, outputs=names, threads=threads,
                                                     out=out))
                c = cpp["batch/%s/%s/threads:%d" % (name, kind, threads)]
                print("| %s | %s | %d | %.1f | %.1f | %.2f | %.1f |" % (
                    name, kind, threads, call * 1e3, c * 1e3, call / c,
                    call / n / model.body_count * 1e9))
    print()
    for name in MODELS:
        model = mb_kinematics.load(os.path.join(ROOT, MODELS[name]))
        q, v, a = states(model, 1000, seed=2)
        ours = best(lambda: model.kinematics(q, v, a, threads=1)) / 1000
        dart = dartpy_loop(name, model, q, v, a)
        print("%s: dartpy loop %.1f us per sample, Model.kinematics %.2f us: %.0fx" % (
            name, dart * 1e6, ours * 1e6, dart / ours))
        if name == "panda":
            pose = best(lambda: model.kinematics(q, v, outputs=["rotation", "origin", "omega",
                                                                "velocity"], threads=1)) / 1000
            for what, tips in (("the hand", ["panda_hand"]), ("every body", model.body_names)):
                kdl = pykdl_loop(model, q, v, tips)
                print("panda: PyKDL loop (%s: pose and velocity) %.1f us per sample, "
                      "Model.kinematics (every body) %.2f us: %.0fx" % (
                          what, kdl * 1e6, pose * 1e6, kdl / pose))
    for name in MODELS:
        for kind, outputs in (("full", FULL), ("pose", POSE)):
            used, asked = peak_memory(name, outputs, n)
            print("%s %s: peak memory of the call %.1f MB, arrays asked for %.1f MB (%.2fx)" % (
                name, kind, used / 1e6, asked / 1e6, used / asked))
    chunk_rows(n)


def parallel_copy(to, source, threads=2):
    """Each array of `source` copied into `to`'s of the same name, the rows split over `threads`
    threads as Model.kinematics splits its samples (numpy's copy releases the GIL)."""
    def run(t):
        for name, x in to.items():
            begin, end = len(x) * t // threads, len(x) * (t + 1) // threads
            np.copyto(x[begin:end], source[name][begin:end])
    pool = [threading.Thread(target=run, args=(t,)) for t in range(threads)]
    for thread in pool:
        thread.start()
    for thread in pool:
        thread.join()


def chunk_rows(n):
    """Human, 2 threads, the full and the all outputs, best (median) of 5: batch_benchmark's
    plain copy of the same bytes, its computation alone (compute/), its state check (check/),
    its writes alone (write/, stream/) and its batch into arrays touched before (with at most
    four samples at once too, batch4/); then five
    rounds of a 2-thread numpy copy of the same bytes into the out= arrays, out= (against that
    copy), fresh arrays (against out=) and chunks of 10,000 rows (kinematics_chunks, against
    out=; and into one chunk's arrays made before, out=); the chunks' peak memory against one
    chunk's arrays. The load average before and after."""
    load = os.getloadavg()
    cpp = cpp_rows("human/(full|all)/threads:2", 5)
    model = mb_kinematics.load(os.path.join(ROOT, MODELS["human"]))
    q, v, a = states(model, n)
    rows = {}
    for kind, names in (("full", FULL), ("all", ALL)):
        fresh0 = model.kinematics(q[:1], v[:1], a[:1], outputs=names)
        # np.ones, as the table above: its memory (np.empty's) gets transparent huge pages, as
        # the fresh arrays' do; np.zeros' got none here (numpy 1.24), and a call took 1.15x as
        # long to write into them (doc/speed.md).
        out = {k: np.ones((n,) + x.shape[1:]) for k, x in fresh0.items()}
        r = {what: cpp["%s/human/%s/threads:2" % (what, kind)]
             for what in ("copy", "compute", "check", "write", "stream", "batch", "batch4")}
        source = {k: np.ones_like(x) for k, x in out.items()}
        r.update(numpy_copy=[], out=[], fresh=[], chunks=[], chunks_out=[])
        chunk_out = {k: np.ones((10000,) + x.shape[1:]) for k, x in fresh0.items()}

        def chunks(**given):
            for _ in model.kinematics_chunks(q, v, a, outputs=names, threads=2, rows=10000,
                                             **given):
                pass
        for _ in range(5):  # one of each per round: the load drifts alike for all five
            r["numpy_copy"] += timings(lambda: parallel_copy(out, source), 1)
            r["out"] += timings(lambda: model.kinematics(q, v, a, outputs=names, threads=2,
                                                         out=out), 1)
            r["fresh"] += timings(lambda: model.kinematics(q, v, a, outputs=names, threads=2), 1)
            r["chunks"] += timings(chunks, 1)
            r["chunks_out"] += timings(lambda: chunks(out=chunk_out), 1)
        out = source = None  # their memory back
        r["memory"] = chunk_memory(n, names)
        r["bytes"] = sum(x.nbytes for x in fresh0.values())
        rows[kind] = r
    print()
    print("load average %.1f before, %.1f after (1 min)" % (load[0], os.getloadavg()[0]))
    print()
    print("| human, 2 threads, ms: best (median) of 5 | full (%.1f KB per sample) | ratio | "
          "all (%.1f KB per sample) | ratio | aim |" % tuple(
              rows[k]["bytes"] / 1e3 for k in ("full", "all")))
    print("|---|---:|---:|---:|---:|---:|")
    lines = (("plain copy of the same bytes (C++ memcpy, copy/)", "copy", None, ""),
             ("the same, into the out= arrays (numpy, 2 threads, interleaved)", "numpy_copy", None,
              ""),
             ("computation alone (C++, compute/)", "compute", "copy", "the copy"),
             ("the state check alone (C++, check/)", "check", "copy", "the copy"),
             ("the writes alone, ordinary stores (C++, write/)", "write", "copy", "the copy"),
             ("the writes alone, streaming stores (C++, stream/)", "stream", "copy", "the copy"),
             ("C++ batch_kinematics, arrays touched before (batch/)", "batch", "copy", "the copy"),
             ("the same, four samples at once at most (batch4/)", "batch4", "batch", "batch/"),
             ("out=", "out", "numpy_copy", "the numpy copy"),
             ("fresh arrays", "fresh", "out", "out="),
             ("kinematics_chunks, rows=10000", "chunks", "out", "out="),
             ("kinematics_chunks, rows=10000, out= (one chunk's arrays, made before)",
              "chunks_out", "out", "out="))
    aims = {"out": "1.25x", "fresh": "1.3x", "chunks": "1.1x", "chunks_out": "1.1x"}
    for label, what, peer, against in lines:
        cells = []
        for kind in ("full", "all"):
            t = rows[kind][what]
            ratio = ("%.2fx %s" % (min(t) / min(rows[kind][peer]), against)) if peer else ""
            if what == "out":  # and against the plain copy of the aim
                ratio += ", %.2fx the C++ one" % (min(t) / min(rows[kind]["copy"]))
            cells += ["%.1f (%.1f)" % (min(t) * 1e3, np.median(t) * 1e3), ratio]
        print("| %s | %s | %s | %s | %s | %s |" % ((label,) + tuple(cells) +
                                                   (aims.get(what, ""),)))
    cells = []
    for kind in ("full", "all"):
        used, chunk = rows[kind]["memory"]
        cells += ["%.1f MB" % (used / 1e6), "%.2fx one chunk's arrays (%.1f MB)" % (
            used / chunk, chunk / 1e6)]
    print("| kinematics_chunks' peak memory | %s | %s | %s | %s | 1x |" % tuple(cells))


def chunk_memory(n, names):
    """A child process: the peak RSS of kinematics_chunks(rows=10000) over n samples above its
    RSS before, and the bytes of one chunk's arrays."""
    code = """
import sys, numpy as np, mb_kinematics
m = mb_kinematics.load(sys.argv[1]); n = int(sys.argv[2]); outputs = sys.argv[3].split(",")
rng = np.random.default_rng(1)
q, v, a = (rng.uniform(-0.5, 0.5, (n, k)) for k in (m.nq, m.nv, m.nv))
def status(key):
    line = next(l for l in open("/proc/self/status") if l.startswith(key))
    return int(line.split()[1]) * 1024
open("/proc/self/clear_refs", "w").write("5")
before = status("VmRSS:")
chunk = 0
for start, out in m.kinematics_chunks(q, v, a, outputs=outputs, threads=2, rows=10000):
    chunk = max(chunk, sum(x.nbytes for x in out.values()))
print(status("VmHWM:") - before, chunk)
"""
    done = subprocess.run([sys.executable, "-c", code, os.path.join(ROOT, MODELS["human"]),
                           str(n), ",".join(names)], capture_output=True, text=True, check=True,
                          cwd="/tmp")
    return tuple(map(int, done.stdout.split()))


if __name__ == "__main__":
    main()
