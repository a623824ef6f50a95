"""mb_kinematics.Recording: a recording's samples as `mbk bag` reads them (doc/python.md,
Recordings), over the compiled one. It pickles as its source: the model and the file with the
reading's options (`Model.read_recording`), or the model and the arrays (`Model.recording`)."""

__all__ = ["Recording"]


class Recording:
    """The samples of a recording, read as `mbk bag` reads them: from a file with
    `Model.read_recording(path, ...)` or from arrays with `Model.recording(times, positions)`.
    Immutable; every attribute is read-only and each call returns new arrays.

    A Recording pickles (multiprocessing, Dask) as its source: the model (itself pickled as its
    file or text and options) and the file name with the reading's options, read again where it
    is unpickled, or the arrays it was made from."""

    __slots__ = ("_core", "_source")

    def __init__(self, core, source):
        """Not for users: `Model.read_recording` and `Model.recording` make Recordings.
        `source`: (function, args) that make it again, for pickle."""
        object.__setattr__(self, "_core", core)
        object.__setattr__(self, "_source", source)

    def __setattr__(self, name, value):
        raise AttributeError("Recording is immutable: %s cannot be set" % name)

    def __delattr__(self, name):
        raise AttributeError("Recording is immutable: %s cannot be deleted" % name)

    def __reduce__(self):
        return self._source

    def __copy__(self):
        return self

    def __deepcopy__(self, memo):
        return self  # immutable: a copy would be the same recording

    @property
    def times(self):
        """(rows,) float64: the samples' stamps (s) as recorded."""
        return self._core.times

    @property
    def positions(self):
        """(rows, nq) float64: the coordinates of each row (NaN where not recorded)."""
        return self._core.positions

    @property
    def velocities(self):
        """(rows, nq) float64: recorded velocities, NaN where not recorded (most recordings)."""
        return self._core.velocities

    @property
    def accelerations(self):
        """(rows, nq) float64: recorded accelerations (a bag's joint_accelerations), NaN where
        not recorded."""
        return self._core.accelerations

    @property
    def grid(self):
        """dict: the stamps' uniform grid: `found` (bool), `moves`, `period` (s), `worst` and
        `tolerance` (s); stamps on a grid to within their rounding are differentiated on it."""
        return self._core.grid

    @property
    def drops(self):
        """dict reason -> count: the samples dropped while reading, as `mbk bag` counts them."""
        return self._core.drops

    @property
    def base(self):
        """None, or the floating base's odometry read with `base_odometry=`: a dict `times`
        (n,), `position`, `linear`, `angular` (n, 3; the twist in the base's frame),
        `orientation` (n, 4: x, y, z, w) and `frame` (R)."""
        return self._core.base

    def __len__(self):
        """The number of rows."""
        return len(self._core.times)

    def __repr__(self):
        times, grid, drops = self._core.times, self._core.grid, self._core.drops
        span = "%.6g-%.6g s" % (times[0], times[-1]) if len(times) else "empty"
        rate = ", %.6g Hz grid" % (1 / grid["period"]) if grid["found"] and grid["period"] > 0 \
            else ""
        dropped = sum(drops.values())
        return "<mb_kinematics.Recording: %d rows x %d coordinates, %s%s%s%s>" % (
            len(times), self._core.positions.shape[1], span, rate,
            ", base odometry" if self._core.base is not None else "",
            ", %d samples dropped" % dropped if dropped else "")
