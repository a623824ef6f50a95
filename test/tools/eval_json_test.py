#!/usr/bin/env python3
"""Every JSON that `mbk eval` writes is JSON: on the models the fuzzers start from (the shipped
URDFs and scenes, the fuzz regressions), on the fuzz corpus of the workspace when a fuzz run has
left one, and on hostile models made here (masses and lengths at a double's limits). A model
`mbk eval` refuses gives one error line and nothing on stdout.

  eval_json_test.py MBK [WORKSPACE]
"""
import glob
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
CORPUS_LIMIT = 2000  # files per harness from a grown corpus: bounds the test's time


def strict_json(text):
    def refuse(constant):
        raise ValueError("not JSON: " + constant)
    return json.loads(text, parse_constant=refuse)


def hostile_models(folder):
    """Models at a double's limits: each either refused or given as valid JSON."""
    link = ('<link name="{0}"><inertial><mass value="{1}"/><origin xyz="{2} 0 0"/>'
            '<inertia ixx="{3}" iyy="{3}" izz="{3}" ixy="0" ixz="0" iyz="0"/></inertial></link>')
    cases = {"huge_mass": ("1.7e308", "0", "1"), "huge_offset": ("1", "1e308", "1"),
             "tiny_mass": ("4.9e-324", "0", "4.9e-324"), "huge_inertia": ("1", "0", "1e308")}
    paths = []
    for name, (mass, x, inertia) in cases.items():
        path = os.path.join(folder, name + ".urdf")
        with open(path, "w") as f:
            f.write('<robot name="r">' + link.format("base", mass, x, inertia) +
                    link.format("arm", mass, x, inertia) +
                    '<joint name="j" type="revolute"><parent link="base"/><child link="arm"/>'
                    '<origin xyz="' + x + ' 0 0"/><axis xyz="0 0 1"/>'
                    '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>')
        paths.append(path)
    return paths


def models(workspace, folder):
    found = []
    for pattern in ("config/*.urdf", "config/*.yaml", "test/ros/*.urdf", "test/robots/*.urdf",
                    "test/io/data/*.yaml", "test/fuzz/regressions/yaml_scene/*"):
        found += sorted(glob.glob(os.path.join(ROOT, pattern)))
    if workspace:
        for harness in ("urdf", "yaml_scene"):
            corpus = sorted(glob.glob(os.path.join(workspace, "fuzz", "corpus", harness, "*")))
            found += corpus[:CORPUS_LIMIT]
    return found + hostile_models(folder)


def main():
    mbk, workspace = sys.argv[1], (sys.argv[2] if len(sys.argv) > 2 else "")
    failures, evaluated, refused = [], 0, 0
    with tempfile.TemporaryDirectory() as folder:
        paths = models(workspace, folder)
        for path in paths:
            run = subprocess.run([mbk, "eval", "--model", path], capture_output=True, timeout=60)
            if run.returncode == 0:
                try:
                    strict_json(run.stdout.decode("utf-8"))
                    evaluated += 1
                except ValueError as error:
                    failures.append("%s: %s" % (path, str(error)[:200]))
            else:
                refused += 1
                lines = run.stderr.decode("utf-8", "replace").strip().splitlines()
                if run.stdout or len(lines) != 1:
                    failures.append("%s: refused with %d stdout bytes and %d stderr lines" % (
                        path, len(run.stdout), len(lines)))
    for failure in failures:
        print("FAIL " + failure)
    print("%d models: %d valid JSON, %d refused, %d failures" % (
        len(paths), evaluated, refused, len(failures)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
