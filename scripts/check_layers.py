#!/usr/bin/env python3
"""The layers of mb_kinematics/ (doc/architecture.md): fails when an #include runs from a lower
layer to a higher one (or across to a peer of the same rank), when core/ or estimation/
includes anything but the C++ library, Eigen and themselves (no ROS), or when headers include
each other (an include loop, named file by file). The Python binding's C++
(python/mb_kinematics/*.cc) is above every layer: it may include any of them, and none it.

  scripts/check_layers.py [SOURCE_ROOT]     SOURCE_ROOT defaults to this repository
"""
import os
import re
import sys

# Lowest first; folders in one tuple share a rank and do not include each other.
LAYERS = [("core",), ("estimation",), ("io",), ("analysis", "viz"), ("messages",),
          ("offline", "ros"), ("rviz", "tools")]
BINDING = ("python", "mb_kinematics")  # the binding's C++, beside its Python package
RANK = {folder: rank for rank, folders in enumerate(LAYERS) for folder in folders}
ROS_FREE = ("core", "estimation")
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')
OWN = re.compile(r"^mb_kinematics/([^/]+)/")


def allowed_system_header(header):
    """A ROS-free folder may include the C++ library (no slash), Eigen and the CPU intrinsics."""
    return "/" not in header or header.startswith(("Eigen/", "unsupported/Eigen/"))


def problems_of(path, folder):
    found = []
    with open(path, encoding="utf-8", errors="replace") as source:
        for number, line in enumerate(source, 1):
            match = INCLUDE.match(line)
            if not match:
                continue
            header = match.group(2)
            where = f"{path}:{number}: {folder}/ includes {header}"
            own = OWN.match(header)
            if own:
                target = own.group(1)
                if target not in RANK:
                    found.append(f"{where}: mb_kinematics/{target}/ is in no layer")
                elif folder in RANK and target != folder and RANK[target] >= RANK[folder]:
                    found.append(f"{where}: {target}/ is not below {folder}/")
            elif folder in ROS_FREE and not allowed_system_header(header):
                found.append(f"{where}: {folder}/ stays ROS-free (C++ library and Eigen only)")
    return found


def own_includes(path):
    """The package's headers that `path` includes, as mb_kinematics/... paths."""
    with open(path, encoding="utf-8", errors="replace") as source:
        return [m.group(2) for m in map(INCLUDE.match, source) if m and OWN.match(m.group(2))]


def include_loops(root, headers):
    """Every include loop among `headers` (mb_kinematics/... paths), each once."""
    graph = {h: [i for i in own_includes(os.path.join(root, h)) if i in headers] for h in headers}
    loops, done, path = [], set(), []

    def visit(header):
        if header in path:
            loop = path[path.index(header):]
            start = loop.index(min(loop))  # one way to name each loop
            loops.append(loop[start:] + loop[:start])
            return
        if header in done:
            return
        path.append(header)
        for included in graph[header]:
            visit(included)
        path.pop()
        done.add(header)

    for header in sorted(graph):
        visit(header)
    return sorted({tuple(loop) for loop in loops})


def main():
    default = os.path.join(os.path.dirname(__file__), "..")
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else default)
    package = os.path.join(root, "mb_kinematics")
    problems = []
    for folder in sorted(os.listdir(package)):
        directory = os.path.join(package, folder)
        if not os.path.isdir(directory):
            continue
        if folder not in RANK:
            problems.append(f"{directory}: a folder in no layer (add it to LAYERS here)")
            continue
        for base, _, files in os.walk(directory):
            for name in sorted(files):
                if name.endswith((".h", ".cc")):
                    problems += problems_of(os.path.join(base, name), folder)
    binding = os.path.join(root, *BINDING)
    for name in sorted(os.listdir(binding)) if os.path.isdir(binding) else []:
        if name.endswith((".h", ".cc")):
            problems += problems_of(os.path.join(binding, name), "python")
    headers = {os.path.relpath(os.path.join(base, name), root)
               for base, _, files in os.walk(package) for name in files if name.endswith(".h")}
    for loop in include_loops(root, headers):
        problems.append("include loop: " + " -> ".join(loop + (loop[0],)))
    for problem in problems:
        print(problem, file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
