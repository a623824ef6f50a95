#!/usr/bin/env python3
"""The Python module's speed (doc/speed.md#python): Model.kinematics on N = 1e5 states of
config/human_body.urdf and test/robots/panda.urdf (a 7-joint arm), full outputs (the default
with accelerations) and poses only, one and two threads, into out= arrays allocated before
(as batch_benchmark's C++ rows, run in the same invocation) and freshly allocated; a Python loop
over PyKDL's chain solvers (panda: the hand's pose and velocity, then every body's) and over dartpy (every body's
pose, velocities and accelerations) on 1000 states; the peak memory of a fresh call (a child
process: its peak RSS during the call, VmHWM reset just before it, above its RSS then) against the bytes of the arrays
asked for. Prints a markdown table. Not a test: the figures depend on the machine's load.

  source devel/setup.bash; /usr/bin/python3 bench/python_batch.py [--samples N] [--in-place-only]
  (run outside the repository's root, which would shadow the package: e.g. cd /tmp first)
"""
import argparse
import json
import os
import subprocess
import sys
import time

import numpy as np

import mb_kinematics

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
MODELS = {"human": "config/human_body.urdf", "panda": "test/robots/panda.urdf"}
POSE = ["rotation", "origin"]


def states(model, n, seed=1):
    rng = np.random.default_rng(seed)
    return (rng.uniform(-0.5, 0.5, (n, model.nq)), rng.uniform(-0.5, 0.5, (n, model.nv)),
            rng.uniform(-0.5, 0.5, (n, model.nv)))


def best(f, repeats=3):
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        f()
        times.append(time.perf_counter() - start)
    return min(times)


def cpp_rows():
    """batch_benchmark's rows (seconds per run of 1e5 samples), from the workspace."""
    for prefix in os.environ.get("CMAKE_PREFIX_PATH", "").split(":"):
        path = os.path.join(prefix, "lib", "mb_kinematics", "batch_benchmark")
        if prefix and os.path.isfile(path):
            out = subprocess.run([path, "--benchmark_format=json", "--benchmark_min_time=1"],
                                 capture_output=True, text=True, check=True).stdout
            return {b["name"].replace("/real_time", ""): b["real_time"] / 1e3
                    for b in json.loads(out)["benchmarks"]}
    raise RuntimeError("batch_benchmark not found: build it and source devel/setup.bash")


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
    cpp = cpp_rows()
    if arguments.in_place_only:
        return chunk_rows(n, cpp)
    print("| model | outputs | threads | Python call, out= (ms) | C++ batch_kinematics (ms) | "
          "Python / C++ | Python, fresh arrays (ms) | ns per sample | ns per body and sample |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name, path in MODELS.items():
        model = mb_kinematics.load(os.path.join(ROOT, path))
        q, v, a = states(model, n)
        for kind, outputs in (("full", None), ("pose", POSE)):
            names = outputs or [k for k in mb_kinematics.OUTPUTS if not k.startswith("partial")]
            fresh0 = model.kinematics(q[:1], v[:1], a[:1], outputs=names)
            out = {k: np.zeros((n,) + x.shape[1:]) for k, x in fresh0.items()}
            for threads in (1, 2):
                call = best(lambda: model.kinematics(q, v, a, outputs=names, threads=threads,
                                                     out=out))
                fresh = best(lambda: model.kinematics(q, v, a, outputs=names, threads=threads))
                c = cpp["batch/%s/%s/threads:%d" % (name, kind, threads)]
                print("| %s | %s | %d | %.1f | %.1f | %.2f | %.1f | %.0f | %.1f |" % (
                    name, kind, threads, call * 1e3, c * 1e3, call / c, fresh * 1e3, call / n * 1e9,
                    call / n / model.body_count * 1e9))
        for threads in (1, 2):
            copy = cpp["copy/%s/full/threads:%d" % (name, threads)]
            print("| %s | copy of the full outputs' bytes | %d | | %.1f | | | %.0f | |" % (
                name, threads, copy * 1e3, copy / n * 1e9))
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
        for kind, outputs in (("full", [k for k in mb_kinematics.OUTPUTS
                                        if not k.startswith("partial")]), ("pose", POSE)):
            used, asked = peak_memory(name, outputs, n)
            print("%s %s: peak memory of the call %.1f MB, arrays asked for %.1f MB (%.2fx)" % (
                name, kind, used / 1e6, asked / 1e6, used / asked))
    chunk_rows(n, cpp)


def chunk_rows(n, cpp):
    """Human, full outputs, 2 threads: out= against the plain copy of the same bytes, fresh
    arrays against out=, chunks of 10,000 rows (kinematics_chunks) against one call, and the
    chunks' peak memory against one chunk's arrays."""
    model = mb_kinematics.load(os.path.join(ROOT, MODELS["human"]))
    q, v, a = states(model, n)
    names = [k for k in mb_kinematics.OUTPUTS if not k.startswith("partial")]
    fresh0 = model.kinematics(q[:1], v[:1], a[:1], outputs=names)
    out = {k: np.zeros((n,) + x.shape[1:]) for k, x in fresh0.items()}
    call = best(lambda: model.kinematics(q, v, a, outputs=names, threads=2, out=out), 5)
    fresh = best(lambda: model.kinematics(q, v, a, outputs=names, threads=2), 5)

    def chunks():
        for _ in model.kinematics_chunks(q, v, a, outputs=names, threads=2, rows=10000):
            pass
    chunked = best(chunks, 5)
    copy = cpp["copy/human/full/threads:2"]
    print()
    print("| human, full outputs, 2 threads | ms | ratio | aim |")
    print("|---|---:|---:|---:|")
    print("| plain copy of the same bytes (C++ memcpy) | %.1f | | |" % (copy * 1e3))
    print("| out= | %.1f | %.2fx the copy | 1.25x |" % (call * 1e3, call / copy))
    print("| fresh arrays | %.1f | %.2fx out= | 1.3x |" % (fresh * 1e3, fresh / call))
    print("| kinematics_chunks, rows=10000 | %.1f | %.2fx out= | 1.1x |" % (
        chunked * 1e3, chunked / call))
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
    used, chunk = map(int, done.stdout.split())
    print("| kinematics_chunks' peak memory | %.1f MB | %.2fx one chunk's arrays (%.1f MB) | 1x |"
          % (used / 1e6, used / chunk, chunk / 1e6))


if __name__ == "__main__":
    main()
