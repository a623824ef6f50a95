#!/usr/bin/env python3
"""doc/speed.md's speed table from one kinematics_benchmark run.

  kinematics_benchmark --benchmark_repetitions=5 --benchmark_out=run.json
  bench/speed_table.py run.json

Per scene: median CPU time per update (ns) of ours and each peer, our full state per body, and
the same-run ratios (ours / peer: below 1 means ours is faster); Pinocchio's full state both with
our coordinates converted in the loop and from its own (full_own_coordinates); first the
machine's load average as the run recorded it.
"""
import json
import sys


def medians(path):
    runs = json.load(open(path))["benchmarks"]
    out = {}
    for r in runs:
        if r.get("run_type") == "aggregate" and r.get("aggregate_name") != "median":
            continue
        name = r.get("run_name", r["name"])
        out[name] = (r["cpu_time"], r.get("bodies"))
    return out


def main():
    m = medians(sys.argv[1])
    load = json.load(open(sys.argv[1]))["context"].get("load_avg")
    if load:
        print("Load average when the run started (1, 5, 15 min): "
              + ", ".join(f"{x:.1f}" for x in load) + "\n")
    scenes = []
    for name in m:
        if name.startswith("ours/") and name.endswith("/recursive/full"):
            scenes.append(name.split("/")[1])

    def t(key):
        return m[key][0] if key in m else None

    def ns(x):
        return "-" if x is None else f"{x:,.0f}"

    def ratio(a, b):
        return "-" if a is None or b is None else f"{a / b:.2f}"

    print("| scene | bodies | ours: pose | ours: full | full per body | Pinocchio: pose | "
          "Pinocchio: full | Pinocchio: full, own coordinates | DART: full | "
          "full / Pinocchio full | full / Pinocchio full, own coordinates | "
          "pose / Pinocchio pose | full / DART full |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for s in scenes:
        pose, full = t(f"ours/{s}/recursive/pose"), t(f"ours/{s}/recursive/full")
        bodies = m[f"ours/{s}/recursive/full"][1]
        pp, pf, df = t(f"pinocchio/{s}/pose"), t(f"pinocchio/{s}/full"), t(f"dart/{s}/full")
        po = t(f"pinocchio/{s}/full_own_coordinates")
        print(f"| {s} | {bodies:,.0f} | {ns(pose)} | {ns(full)} | {full / bodies:.1f} | {ns(pp)} | "
              f"{ns(pf)} | {ns(po)} | {ns(df)} | {ratio(full, pf)} | {ratio(full, po)} | "
              f"{ratio(pose, pp)} | {ratio(full, df)} |")

if __name__ == "__main__":
    main()
