"""mbk batch --subjects FILE.csv (doc/batch.md#many-subjects): per recording, the options of
its subject, so that recordings in several units and of several people run in one batch. A CSV
with a header: `path` (a file or a glob, relative to the CSV's folder) and any of `scale`,
`body_mass`, `sex` (an empty cell: the command line's option). A recording takes the first row
whose path names it."""
import csv
import glob
import os

from mb_kinematics import _core
from mb_kinematics.batch_inputs import BatchError

# column -> mbk bag's option
OPTIONS = {"scale": "--scale", "body_mass": "--body-mass", "sex": "--sex"}
COLUMNS = ["path"] + list(OPTIONS)


def _options(where, row):
    """mbk bag's options of one row: {"--scale": "0.01", ...}, its empty cells left out; checked
    as mbk bag checks them (BatchError with its message)."""
    cells = {column: (row.get(column) or "").strip() for column in OPTIONS}
    try:
        _core.check_bvh_options(cells["scale"], cells["body_mass"], cells["sex"])
    except ValueError as e:
        raise BatchError("%s: %s" % (where, e)) from None
    return {OPTIONS[column]: text for column, text in cells.items() if text}


def read_subjects(path):
    """The rows of a subjects CSV: (where, absolute path or glob, options). BatchError, one
    line naming the file (and line), for a file that cannot be read, a header without `path` or
    with a column not in COLUMNS, a bad value."""
    try:
        with open(path, newline="", encoding="utf-8") as f:
            reader = csv.DictReader(f)
            header = reader.fieldnames or []
            unknown = [c for c in header if c not in COLUMNS]
            if unknown or "path" not in header:
                raise BatchError("%s: %s (the columns: %s)" % (
                    path, "unknown column '%s'" % unknown[0] if unknown else "no column 'path'",
                    ", ".join(COLUMNS)))
            base = os.path.dirname(os.path.abspath(path))
            rows = []
            for row in reader:
                where = "%s:%d" % (path, reader.line_num)
                if None in row or not (row["path"] or "").strip():
                    raise BatchError("%s: %s" % (where, "more cells than columns" if None in row
                                                 else "no path"))
                rows.append((where, os.path.join(base, row["path"].strip()),
                             _options(where, row)))
    except (OSError, UnicodeDecodeError, csv.Error) as e:
        raise BatchError("%s: cannot read the subjects: %s" % (path, e))
    return rows


def subject_options(rows, inputs):
    """input -> mbk bag's options of its subject, for find_inputs' (input, stem) pairs: each
    input takes the first row that names it. BatchError for a row that names no input and for a
    row with options that names an input other than a .bvh file (whose model is not its own)."""
    real = {os.path.realpath(path): path for path, _ in inputs}
    chosen = {}
    for where, pattern, options in rows:
        named = [real[p] for p in sorted({os.path.realpath(m) for m in
                                          glob.glob(pattern, recursive=True)}) if p in real]
        if not named:
            raise BatchError("%s: %s names no input" % (where, pattern))
        for path in named:
            if options and not path.endswith(".bvh"):
                raise BatchError("%s: %s: scale, body_mass and sex apply to .bvh inputs"
                                 % (where, path))
            chosen.setdefault(path, options)
    return chosen
