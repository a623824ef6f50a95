"""mbk batch's inputs (doc/batch.md): the recordings that files, folders and list files name,
each with the path of its outputs below --out-dir."""
import os

from mb_kinematics.batch_job import STATE

EXTENSIONS = (".bag", ".csv", ".bvh")
SUMMARY = "summary.csv"  # beside the outputs: no input may be written over it
SIDE_FILES = (".errors", ".sample_errors")  # OUT.csv's side files: OUT.errors.csv, ...


class BatchError(ValueError):
    """A wrong command line or input list: nothing is run."""


def _walk(folder):
    """The recordings under `folder`, recursively, in sorted order."""
    found = []
    for top, dirs, files in os.walk(folder):
        dirs[:] = sorted(d for d in dirs if d != STATE)
        found += [os.path.join(top, f) for f in sorted(files) if f.endswith(EXTENSIONS)]
    return found


def _list_file(path, seen):
    """The entries of a list file: one path a line (relative to the list file's folder), blank
    lines and lines starting with # skipped."""
    base = os.path.dirname(os.path.abspath(path))
    try:
        with open(path, encoding="utf-8") as f:
            lines = [line.strip() for line in f]
    except (OSError, UnicodeDecodeError) as e:
        raise BatchError("%s: cannot read the list: %s" % (path, e))
    entries = []
    for line in lines:
        if line and not line.startswith("#"):
            entries += _expand(os.path.join(base, line), seen)
    return entries


def _expand(path, seen):
    """(input, path of its outputs relative to --out-dir without extension) for an argument."""
    if os.path.isdir(path):
        return [(f, os.path.splitext(os.path.relpath(f, path))[0]) for f in _walk(path)]
    if path.endswith(EXTENSIONS) and os.path.isfile(path):
        return [(path, os.path.splitext(os.path.basename(path))[0])]
    if os.path.isfile(path):
        real = os.path.realpath(path)
        if real in seen:
            raise BatchError("%s: a list file that lists itself" % path)
        return _list_file(path, seen | {real})
    raise BatchError("%s: no such file or folder" % path)


def find_inputs(paths, out_dir):
    """(input, relative output stem) of every recording the arguments name, in their order; the
    inputs under `out_dir` are left out. Raises BatchError for a missing path, no recording at
    all, or two inputs whose outputs would have the same name."""
    out = os.path.realpath(out_dir)
    stems, seen, found = {os.path.splitext(SUMMARY)[0]: SUMMARY}, set(), []
    for path in paths:
        for item, stem in _expand(path, frozenset()):
            try:
                os.stat(item)
            except OSError as e:  # a dangling link, a link loop
                raise BatchError("%s: %s" % (item, e.strerror))
            real = os.path.realpath(item)
            if real == out or real.startswith(out + os.sep) or real in seen:
                continue
            key = os.path.normpath(stem)
            for name in [key] + [key + side for side in SIDE_FILES]:  # mbk bag --csv's too
                if name in stems:
                    raise BatchError("%s and %s: both would be written as %s in --out-dir"
                                     % (stems[name], item, name))
            for name in [key] + [key + side for side in SIDE_FILES]:
                stems[name] = item
            seen.add(real)
            found.append((item, key))
    if not found:
        raise BatchError("no recording (%s) in %s" % (", ".join(EXTENSIONS), " ".join(paths)))
    return found
