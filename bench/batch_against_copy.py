#!/usr/bin/env python3
"""The batch against a plain copy of the same bytes, process by process (doc/speed.md#python):
on this virtual machine the copy's time has two levels that change from one process to the next
(the memory the process is given), so each run of batch_benchmark times `batch/` and `copy/`
(human, full and all outputs, 2 threads, medians of 3) in the same process, and this prints each
run's ratio and a summary. Not a test: the figures depend on the machine's load.

  source devel/setup.bash; /usr/bin/python3 bench/batch_against_copy.py [--runs 18] [--aim 1.25]
"""
import argparse
import json
import statistics
import subprocess

from python_batch import batch_benchmark  # beside this script


def one_run(path):
    """{(row, outputs): median ms} of one batch_benchmark process."""
    out = subprocess.run([path, "--benchmark_format=json", "--benchmark_min_time=0.5",
                          "--benchmark_repetitions=3", "--benchmark_report_aggregates_only=true",
                          "--benchmark_filter=^(copy|batch)/human/(full|all)/threads:2"],
                         capture_output=True, text=True, check=True).stdout
    times = {}
    for b in json.loads(out)["benchmarks"]:
        if b.get("aggregate_name") == "median":
            row, _, outputs = b["run_name"].split("/")[:3]
            scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[b["time_unit"]]
            times[(row, outputs)] = b["real_time"] * scale  # ms
    return times


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--runs", type=int, default=18)
    parser.add_argument("--aim", type=float, default=1.25)
    arguments = parser.parse_args()
    path = batch_benchmark()
    print("| run | full: batch/ (ms) | copy/ | ratio | all: batch/ (ms) | copy/ | ratio |")
    print("|---:|---:|---:|---:|---:|---:|---:|")
    ratios = {"full": [], "all": []}
    for run in range(1, arguments.runs + 1):
        t = one_run(path)
        cells = []
        for outputs in ("full", "all"):
            batch, copy = t[("batch", outputs)], t[("copy", outputs)]
            ratios[outputs].append(batch / copy)
            cells += ["%.1f" % batch, "%.1f" % copy, "%.2f" % (batch / copy)]
        print("| %d | %s |" % (run, " | ".join(cells)), flush=True)
    print()
    for outputs, r in ratios.items():
        print("%s: batch/ within %.2fx of copy/ in %d of %d runs; ratios %.2f to %.2f, median %.2f"
              % (outputs, arguments.aim, sum(x <= arguments.aim for x in r), len(r), min(r),
                 max(r), statistics.median(r)))


if __name__ == "__main__":
    main()
