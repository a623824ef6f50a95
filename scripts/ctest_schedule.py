#!/usr/bin/env python3
"""ctest's schedule in CPU seconds (doc/building.md, "Where the time goes").

  ctest_schedule.py measure BUILD [-jN] [REGEX]
      Runs the tests of BUILD (a configured build folder) as `ctest -jN` starts them: in
      decreasing COST, when their slots (PROCESSORS) and resource locks are free, RUN_SERIAL
      alone. One line per test as it ends: its name, wall seconds, user and system CPU seconds
      (its process and the children it waited for), exit status and the second it ended; the
      sums last. Output and timeouts are not kept: ctest itself says why a test fails.
  ctest_schedule.py simulate BUILD MEASURED N... [REGEX=COST...]
      The same schedule replayed on two cores for each N (slots), from a `measure` output: each
      test needs the wall seconds it took and uses the cores at its measured rate (CPU / wall);
      tests running together share the two cores. REGEX=COST gives the matching tests that COST.
      Prints the wall seconds and how busy the cores were on average.
"""
import json
import os
import re
import subprocess
import sys
import time

CORES = 2.0


def tests_of(build):
    """The tests of BUILD in ctest's order of start on a clean clone (COST, then definition)."""
    listing = json.loads(subprocess.check_output(["ctest", "--show-only=json-v1"], cwd=build))
    tests = []
    for order, test in enumerate(listing["tests"]):
        props = {p["name"]: p["value"] for p in test.get("properties", [])}
        tests.append({"name": test["name"], "command": test["command"], "order": order,
                      "cost": float(props.get("COST", 0)),
                      "slots": int(props.get("PROCESSORS", 1)),
                      "locks": set(props.get("RESOURCE_LOCK", [])),
                      "serial": bool(props.get("RUN_SERIAL", False)),
                      "env": dict(e.split("=", 1) for e in props.get("ENVIRONMENT", [])),
                      "cwd": props.get("WORKING_DIRECTORY", build)})
    return tests


def in_start_order(tests):
    return sorted(tests, key=lambda t: (-t["cost"], t["order"]))


def can_start(test, running, jobs):
    """As ctest: a RUN_SERIAL test alone, no shared lock, its slots free (or nothing running)."""
    if running and (test["serial"] or any(r["serial"] for r in running)):
        return False
    if any(test["locks"] & r["locks"] for r in running):
        return False
    used = sum(min(r["slots"], jobs) for r in running)
    return not running or used + min(test["slots"], jobs) <= jobs


def startable(todo, running, jobs):
    """The first test of `todo` that can start now, or None."""
    return next((t for t in todo if can_start(t, running, jobs)), None)


def measure(build, jobs, regex):
    todo = in_start_order([t for t in tests_of(build) if re.search(regex, t["name"])])
    running, began, cpu = {}, time.monotonic(), [0.0, 0.0]
    while todo or running:
        test = startable(todo, list(running.values()), jobs)
        while test:
            process = subprocess.Popen(test["command"], cwd=test["cwd"],
                                       env=dict(os.environ, **test["env"]),
                                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            test["start"] = time.monotonic()
            running[process.pid] = test
            todo.remove(test)
            test = startable(todo, list(running.values()), jobs)
        pid, status, usage = os.wait4(-1, 0)  # the first test to end, with its CPU seconds
        test = running.pop(pid, None)
        if test is None:
            continue
        cpu[0] += usage.ru_utime
        cpu[1] += usage.ru_stime
        now = time.monotonic()
        print("%-70s %7.1f %7.1f %6.1f %4d  @%.0f" % (
            test["name"][:70], now - test["start"], usage.ru_utime, usage.ru_stime,
            os.waitstatus_to_exitcode(status), now - began), flush=True)
    print("TOTAL wall %.1f user %.1f sys %.1f" % (time.monotonic() - began, cpu[0], cpu[1]))


def measured_lengths(path):
    """name -> (wall seconds, CPU seconds) of a `measure` output."""
    line = re.compile(r"(\S+)\s+([\d.]+)\s+([\d.]+)\s+([\d.]+)\s+(-?\d+)\s+@")
    found = {}
    for text in open(path):
        m = line.match(text)
        if m:
            found[m.group(1)] = (float(m.group(2)), float(m.group(3)) + float(m.group(4)))
    return found


def simulate(tests, jobs):
    """(wall seconds, average busy cores) of `tests` (each with "work" seconds and "rate" cores)
    run on two cores with `jobs` slots."""
    todo, running, now, busy = in_start_order([dict(t) for t in tests]), [], 0.0, 0.0
    while todo or running:
        test = startable(todo, running, jobs)
        while test:
            test["left"] = test["work"]
            running.append(test)
            todo.remove(test)
            test = startable(todo, running, jobs)
        demand = sum(t["rate"] for t in running)
        speed = min(1.0, CORES / demand) if demand > 0 else 1.0
        step = min(t["left"] for t in running) / speed  # until the next test ends
        now += step
        busy += min(demand, CORES) * step
        for t in running:
            t["left"] -= step * speed
        running = [t for t in running if t["left"] > 1e-9]
    return now, busy / now


def simulate_main(build, measured, args):
    lengths = measured_lengths(measured)
    costs = [a.split("=", 1) for a in args if "=" in a]
    tests = tests_of(build)
    for test in tests:
        wall, cpu = lengths.get(test["name"][:70], (1.0, 0.5))  # a test not measured: 1 s
        test["work"], test["rate"] = wall, min(cpu / max(wall, 0.1), CORES)
        for regex, cost in costs:
            if re.search(regex, test["name"]):
                test["cost"] = float(cost)
    for jobs in [int(a) for a in args if "=" not in a]:
        print("-j%d: %.0f s, cores busy %.2f on average" % ((jobs,) + simulate(tests, jobs)))


def main(argv):
    if len(argv) >= 2 and argv[0] == "measure":
        jobs = int(argv[2][2:]) if len(argv) > 2 and argv[2].startswith("-j") else 6
        measure(argv[1], jobs, argv[-1] if len(argv) > 2 and not argv[-1].startswith("-j")
                else "")
    elif len(argv) >= 4 and argv[0] == "simulate":
        simulate_main(argv[1], argv[2], argv[3:])
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main(sys.argv[1:])
