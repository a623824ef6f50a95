#!/usr/bin/env python3
"""ctest update_once: the update in double (forward_kinematics<double>) is compiled in one object
of the build, core/kinematics_double.cc's, and in no other (doc/building.md): a file that includes
core/kinematics.h rather than core/kinematics_double.h and runs the update compiles its own copy,
about 27 CPU seconds at -O3 each. Fails naming every other object that defines it.

  update_once_test.py BUILD_DIR
"""
import os
import subprocess
import sys

# The instantiation itself, or, where the compiler inlined it whole, the run-time CPU check that
# only the update's dispatch uses; or its portable copy alone (forward_kinematics_at<LEVEL,
# double, false>), which kinematics_double.h also declares extern.
SIGNS = ("mbk::forward_kinematics<double>(", "guard variable for mbk::detail::has_avx2()",
         ", double, false>(mbk::Model const&")
HOME = "kinematics_double.cc.o"


def objects(build_dir):
    for folder, _, files in os.walk(build_dir):
        for name in files:
            if name.endswith(".o"):
                yield os.path.join(folder, name)


# The identifiers of SIGNS as they stand in a mangled name: only the symbols holding one are
# demangled (demangling every symbol of every object was most of this test's time).
MANGLED = ("forward_kinematics", "has_avx2")


def defining_update(paths):
    """The objects of PATHS that hold the update's code, not only a call to mbk_core's."""
    # One nm for all the objects, each line prefixed with its object (-A: "path: symbol").
    listing = subprocess.run(["nm", "-A", "--defined-only", *paths], capture_output=True,
                             text=True, check=True).stdout
    lines = [line for line in listing.splitlines() if any(word in line for word in MANGLED)]
    demangled = subprocess.run(["c++filt"], input="\n".join(lines), capture_output=True,
                               text=True, check=True).stdout.splitlines()
    found = set()
    for line in demangled:
        path = next((p for p in paths if line.startswith(p + ":")), None)
        if path is not None and any(sign in line for sign in SIGNS):
            found.add(path)
    return found


def main():
    build_dir = sys.argv[1]
    paths = sorted(objects(build_dir))
    found = defining_update(paths)
    home = [path for path in found if os.path.basename(path) == HOME]
    others = sorted(os.path.relpath(path, build_dir) for path in found if path not in home)
    if not home:
        print(f"no {HOME} defining forward_kinematics<double> under {build_dir}")
        return 1
    if others:
        print("forward_kinematics<double> compiled again (include core/kinematics_double.h):")
        print("\n".join("  " + path for path in others))
        return 1
    print(f"forward_kinematics<double> compiled once, in {os.path.relpath(home[0], build_dir)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
