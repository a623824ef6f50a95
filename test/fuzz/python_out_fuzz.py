#!/usr/bin/python3
"""A random-search fuzzer of Model.kinematics' out= arrays (doc/reliability.md), run by
scripts/fuzz.sh beside the libFuzzer harnesses: each case draws a model, samples, outputs and
for each output an array to write into: a fresh one, a view into a buffer that q, velocity or
another output also live in (overlapping or not), or one of the wrong dtype, shape, order or
writeability; one case in 50 has enough samples for the call to stream its rows. Property: the
call raises ValueError or TypeError, or every array holds the same bits as fresh arrays written
in place (calls of at most 64 samples); a crash, another exception or other numbers is a finding
(the case's seed is printed; `--case SEED` replays it).

    python_out_fuzz.py [--seconds S | --runs N] [--seed S] [--case SEED]
"""
import argparse
import os
import sys
import time

import numpy as np

import mb_kinematics

SOURCE = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
MODELS = ["config/human_body.urdf", "config/ten_body.yaml", "test/robots/panda.urdf"]
KINDS = ["fresh", "fresh", "shared", "shared", "dtype", "shape", "strided", "read-only"]


# Bytes of outputs above which a call streams its rows (kBatchStreamBytes,
# offline/batch_kinematics.h), and the samples of a case drawn above it.
STREAMED_BYTES = 16 << 20
MOST_STREAMED_SAMPLES = 40000


def draw_case(rng, models):
    model = models[rng.integers(len(models))]
    single = rng.random() < 0.2
    velocity, acceleration = rng.random() < 0.7, rng.random() < 0.7
    level = 2 if velocity and acceleration else 1 if velocity else 0
    allowed = [n for n in mb_kinematics.OUTPUTS
               if mb_kinematics._TRAITS[n]["level"] <= level]
    outputs = sorted(set(rng.choice(allowed, size=int(rng.integers(1, 4))).tolist()))
    samples = int(rng.integers(0, 6))
    if not single and rng.random() < 0.02:  # enough samples for streamed rows, where it takes few
        per_sample = sum(8 * int(np.prod(shaped(model, n, 1, True))) for n in outputs)
        samples = STREAMED_BYTES // per_sample + 1 + int(rng.integers(0, 3))
        if samples > MOST_STREAMED_SAMPLES:
            samples = int(rng.integers(0, 6))
    rows = 1 if single else samples
    q = rng.uniform(-1.5, 1.5, (rows, model.nq))
    v = rng.uniform(-2, 2, (rows, model.nv)) if velocity else None
    a = rng.uniform(-5, 5, (rows, model.nv)) if velocity and acceleration else None
    return model, single, q, v, a, outputs


def shaped(model, name, rows, single):
    shape = mb_kinematics._shape(model, name, rows, model.body_count)
    return shape[1:] if single else shape


def make_out(rng, model, outputs, rows, single, q, v):
    """out= arrays of random kinds; q and v moved into the shared buffer when drawn so."""
    sizes = [int(np.prod(shaped(model, n, rows, single))) for n in outputs]
    buffer = np.zeros(sum(sizes) + q.size + (v.size if v is not None else 0) + 16)
    offset = lambda: int(rng.integers(0, 16))  # noqa: E731: overlaps where offsets meet
    if rng.random() < 0.5:
        start = offset()
        q = buffer[start:start + q.size].reshape(q.shape)
        q[:] = rng.uniform(-1.5, 1.5, q.shape)
    if v is not None and rng.random() < 0.5:
        start = offset()
        moved = buffer[start:start + v.size].reshape(v.shape)
        moved[:] = v
        v = moved
    out = {}
    for name, size in zip(outputs, sizes):
        shape, kind = shaped(model, name, rows, single), KINDS[rng.integers(len(KINDS))]
        if kind == "shared":
            start = int(rng.integers(0, len(buffer) - size + 1))
            out[name] = buffer[start:start + size].reshape(shape)
        elif kind == "dtype":
            out[name] = np.zeros(shape, dtype=np.float32)
        elif kind == "shape":
            out[name] = np.zeros((size + 1,))
        elif kind == "strided":
            out[name] = np.zeros(shape + (2,))[..., 0]
        else:
            out[name] = np.zeros(shape)
            out[name].setflags(write=kind != "read-only")
    return q, v, out


def in_place(model, args, outputs, single):
    """The outputs computed into fresh arrays in calls small enough to be written in place."""
    if single or len(args[0]) <= 64:
        return model.kinematics(*args, outputs=outputs)
    chunks = [{n: x.copy() for n, x in out.items()}  # each chunk reuses the first's arrays
              for _, out in model.kinematics_chunks(*args, outputs=outputs, rows=64)]
    return {n: np.concatenate([c[n] for c in chunks]) for n in outputs}


def one_case(seed, models):
    rng = np.random.default_rng(seed)
    model, single, q, v, a, outputs = draw_case(rng, models)
    rows = q.shape[0]
    q, v, out = make_out(rng, model, outputs, rows, single, q, v)
    args = (q[0] if single else q, None if v is None else (v[0] if single else v),
            None if a is None else (a[0] if single else a))
    expected = in_place(model, [None if x is None else x.copy() for x in args], outputs, single)
    try:
        got = model.kinematics(*args, outputs=outputs, out=out,
                               threads=int(rng.integers(1, 4)))
    except (ValueError, TypeError):
        return
    for name in outputs:
        if not np.array_equal(got[name], expected[name], equal_nan=True):
            raise AssertionError("%s: other numbers than with fresh arrays" % name)
        if out[name].size and not np.shares_memory(got[name], out[name]):
            raise AssertionError("%s: not written into out=" % name)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--seconds", type=float)
    p.add_argument("--runs", type=int)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--case", type=int, help="one case, by the seed a finding names")
    args = p.parse_args()
    if args.case is not None:
        args.seed, args.runs = args.case, 1
    models = [mb_kinematics.load(os.path.join(SOURCE, m)) for m in MODELS]
    deadline = time.monotonic() + (args.seconds or 0)
    runs = 0
    while (args.runs is not None and runs < args.runs) or (
            args.runs is None and time.monotonic() < deadline):
        seed = args.seed if args.case is not None else args.seed * 1000003 + runs
        try:
            one_case(seed, models)
        except Exception as e:  # anything but the refusals one_case expects
            print("python out= fuzz: FINDING after %d runs (replay: --case %d): %s: %s"
                  % (runs, seed, type(e).__name__, e))
            return 1
        runs += 1
    print("python out= fuzz: %d runs, no finding" % runs)
    return 0


if __name__ == "__main__":
    sys.exit(main())
