#!/usr/bin/env python3
"""ctest layer_includes: scripts/check_layers.py passes on this tree, and fails, naming the file,
line and both layers, on a copy with a planted upward include, on a ROS header in core/, on the
Python binding's C++ (python/mb_kinematics/_core.cc) including a folder in no layer and on two
headers that include each other."""
import os
import shutil
import subprocess
import sys
import tempfile

SOURCE = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
CHECK = os.path.join(SOURCE, "scripts", "check_layers.py")


def check(root):
    run = subprocess.run([sys.executable, CHECK, root], capture_output=True, text=True)
    return run.returncode, run.stderr


def planted(tree, path, line):
    with open(os.path.join(tree, "mb_kinematics", path), "a", encoding="utf-8") as source:
        source.write(line + "\n")


def main():
    failures = []
    code, err = check(SOURCE)
    if code != 0:
        failures.append("this tree breaks the layers:\n" + err)
    with tempfile.TemporaryDirectory() as tmp:
        tree = os.path.join(tmp, "src")
        shutil.copytree(os.path.join(SOURCE, "mb_kinematics"), os.path.join(tree, "mb_kinematics"))
        for path, line, expected in [
            ("offline/bag_output.h", '#include "mb_kinematics/ros/outputs/output.h"',
             "offline/bag_output.h:"),
            ("core/model.h", '#include "mb_kinematics/estimation/derivative_estimator.h"',
             "estimation/ is not below core/"),
            ("estimation/kalman_estimator.h", "#include <ros/time.h>", "stays ROS-free"),
            ("core/data.h", '#include "mb_kinematics/core/kinematics.h"', "include loop: "
             "mb_kinematics/core/data.h -> mb_kinematics/core/kinematics.h -> "
             "mb_kinematics/core/data.h")]:
            shutil.copy(os.path.join(SOURCE, "mb_kinematics", path),
                        os.path.join(tree, "mb_kinematics", path))
            planted(tree, path, line)
            code, err = check(tree)
            if code == 0 or expected not in err:
                failures.append(f"planted {line} in {path}: exit {code}, {err!r}")
            shutil.copy(os.path.join(SOURCE, "mb_kinematics", path),
                        os.path.join(tree, "mb_kinematics", path))
        binding = os.path.join(tree, "python", "mb_kinematics")
        os.makedirs(binding)
        shutil.copy(os.path.join(SOURCE, "python", "mb_kinematics", "_core.cc"), binding)
        with open(os.path.join(binding, "_core.cc"), "a", encoding="utf-8") as source:
            source.write('#include "mb_kinematics/python/binding.h"\n')
        code, err = check(tree)
        if code == 0 or "_core.cc:" not in err or "python/ is in no layer" not in err:
            failures.append(f"planted a binding include in _core.cc: exit {code}, {err!r}")
    for failure in failures:
        print(failure, file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
