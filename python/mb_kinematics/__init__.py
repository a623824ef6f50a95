"""mb_kinematics from Python (doc/python.md): load a model, then the kinematics of N joint states
in one call into numpy arrays named as `mbk eval`'s JSON.

    import mb_kinematics
    model = mb_kinematics.load("config/human_body.urdf")
    out = model.kinematics(q, velocity=qd, acceleration=qdd)   # q: (N, nq) or (nq,)
    out["rotation"]        # (N, bodies, 3, 3), S0K of every body in R

The computation is C++ (offline/batch_kinematics.h, the loaders of io/); this package checks the
arguments, names what is wrong (ValueError, TypeError) and makes the arrays.
"""
import errno
import hashlib
import operator
import os
import pkgutil

import numpy as np

try:
    from mb_kinematics import _core
except ImportError:  # imported from the source folder first on sys.path (a devel space's child
    # processes, e.g. Dask's workers, inherit its sys.path): _core is in the devel space's folder
    __path__ = pkgutil.extend_path(__path__, __name__)
    from mb_kinematics import _core

from mb_kinematics.recording import Recording  # noqa: E402 (after _core's search)

__all__ = ["load", "Model", "OUTPUTS", "OPT_IN", "Recording", "angles", "release_memory"]
#: The package's version (package.xml's).
__version__ = _core.__version__


def __dir__():
    """The public names only (the modules this one uses are not part of it)."""
    return sorted(set(__all__) | {"__version__"})

_TRAITS = _core.field_traits()
_POSE, _VELOCITY, _ACCELERATION = 0, 1, 2
#: Every output `Model.kinematics` can write, in its order.
OUTPUTS = tuple(_TRAITS)
_PARTIALS = tuple(name for name in OUTPUTS if name.startswith("partial_"))
MOST_THREADS = 1024  # as mbk bag --threads
#: Written only when asked for by name: the partial velocities, the segment frames (`*_body`)
#: and the joint motion (`relative_*`).
OPT_IN = tuple(name for name in OUTPUTS if _TRAITS[name]["opt_in"])


def load(path_or_text, scale=None, body_mass=None, sex=None, segments=None, anthropometry=None):
    """The model of a file (.urdf, .xml, .sdf, .yaml, .bvh) or of a text (URDF, MJCF or SDFormat
    XML, e.g. rospy.get_param("robot_description"), or a YAML scene). scale (metres per file
    unit), body_mass (kg), sex ("male"/"female"), segments (a YAML map of joints to segments,
    with body_mass) and anthropometry ("de_leva", the default, or "dempster": the segment table,
    with body_mass) apply to a .bvh file only. Raises ValueError with the loader's one-line
    message."""
    if isinstance(path_or_text, os.PathLike):
        path_or_text = os.fspath(path_or_text)
    if not isinstance(path_or_text, str):
        raise TypeError("path_or_text: a file name or a model text (str), not %s"
                        % type(path_or_text).__name__)
    scale, body_mass = _number(scale, "scale"), _number(body_mass, "body_mass")
    if sex is not None and not isinstance(sex, str):
        raise TypeError("sex: 'male' or 'female', not %s" % type(sex).__name__)
    if isinstance(segments, os.PathLike):
        segments = os.fspath(segments)
    if segments is not None and not isinstance(segments, str):
        raise TypeError("segments: a file name (str), not %s" % type(segments).__name__)
    if anthropometry is not None and not isinstance(anthropometry, str):
        raise TypeError("anthropometry: 'de_leva' or 'dempster', not %s"
                        % type(anthropometry).__name__)
    if anthropometry is not None and not body_mass:
        raise ValueError("anthropometry chooses the masses' table: it needs body_mass")
    text = _core.is_model_text(path_or_text)
    core = _missing_file_checked(_core.load, None if text else path_or_text, path_or_text, scale,
                                 body_mass, sex, segments, anthropometry=anthropometry)
    model = Model(core, 1.0 if scale is None else float(scale))
    source = path_or_text if text else os.path.abspath(path_or_text)  # from any folder
    segments = None if segments is None else os.path.abspath(segments)
    model._source = (source, scale, body_mass, sex, segments, anthropometry,
                     None if text else _file_digest(source))
    return model


def release_memory():
    """Hands the kernel back the memory of released output arrays that the module keeps for the
    next calls' fresh arrays (doc/python.md, Memory); returns its bytes."""
    return _core.release_memory()


def angles(rotation, order):
    """Cardan/Euler angles (rad) of rotation matrices, e.g. kinematics()' `relative_rotation`
    (N, B, 3, 3) for joint angles (doc/python.md). order: one of the 12 orders ("XYZ", "ZXY",
    ..., "ZXZ", or digits as "312") for every matrix, or for (N, B, 3, 3) a sequence of B orders,
    one per body. Returns (..., 3): alpha, beta, gamma with R = R_a1(alpha) R_a2(beta)
    R_a3(gamma) (turns about the moving axes). Continuous along the first axis: the first
    sample's principal angles (alpha, gamma in [-pi, pi]; beta in [-pi/2, pi/2], proper Euler
    orders [0, pi]), each next sample's the set nearest the one before (no 2 pi jumps; at gimbal
    lock alpha stays). One (3, 3) matrix gives its principal angles."""
    r = _real(rotation, "rotation")
    if r.ndim < 2 or r.shape[-2:] != (3, 3):
        raise ValueError("rotation: shape %s, expected (..., 3, 3)" % (r.shape,))
    orders = [order] if isinstance(order, str) else list(order)
    if not all(isinstance(o, str) for o in orders):
        raise TypeError("order: an order name such as 'ZXY', or a sequence of them")
    if len(orders) != 1 and (r.ndim != 4 or len(orders) != r.shape[1]):
        raise ValueError("order: %d orders for rotations of shape %s (one, or one per body of "
                         "(N, B, 3, 3))" % (len(orders), r.shape))
    rows = np.ascontiguousarray(r.reshape((1 if r.ndim == 2 else r.shape[0], -1, 3, 3)),
                                dtype=np.float64)
    if not np.isfinite(rows).all():
        raise ValueError("rotation: not finite")
    gram = np.einsum("...ji,...jk->...ik", rows, rows) - np.eye(3)
    bad = (np.abs(gram).max(axis=(-2, -1)) > 1e-6) | (np.linalg.det(rows) <= 0)
    if bad.any():
        raise ValueError("rotation: not a rotation matrix at index %s (orthonormal, det 1)"
                         % (np.unravel_index(int(np.argmax(bad)), r.shape[:-2]),))
    try:
        out = _core.euler_angles(rows, orders)
    except ValueError as e:
        raise ValueError("order: %s" % e) from None
    return out.reshape(r.shape[:-2] + (3,))


class _NoSuchFile(FileNotFoundError, ValueError):
    """A missing model or recording file: FileNotFoundError, and a ValueError as every other
    loader error (as io.UnsupportedOperation is both an OSError and a ValueError)."""


# Shown (tracebacks) and pickled as the FileNotFoundError it is.
_NoSuchFile.__module__, _NoSuchFile.__name__, _NoSuchFile.__qualname__ = (
    "builtins", "FileNotFoundError", "FileNotFoundError")


def _missing_file_checked(call, path, *args, **kwargs):
    """call(*args, **kwargs); the loader's ValueError about a `path` that does not exist as
    FileNotFoundError, with the loader's message."""
    try:
        return call(*args, **kwargs)
    except ValueError as e:
        if path is None or os.path.exists(path):
            raise
        raise _NoSuchFile(errno.ENOENT, str(e), path) from None


def _file_digest(path):
    """The SHA-256 of a file's bytes."""
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def _load_pickled(path_or_text, scale, body_mass, sex, segments, anthropometry, digest):
    """A pickled Model made again from its source: the same file (same bytes) or text."""
    if digest is not None and not os.path.exists(path_or_text):
        raise _NoSuchFile(errno.ENOENT, "the pickled model's file: no such file", path_or_text)
    if digest is not None and _file_digest(path_or_text) != digest:
        raise ValueError("%s: the model file changed since the model was pickled" % path_or_text)
    return load(path_or_text, scale, body_mass, sex, segments, anthropometry)


class Model:
    """A loaded model: its bodies k = 1..N (body_names[k - 1]), coordinates and speeds; `scale`,
    the metres per file unit it was loaded with (1 but for a .bvh file given another).
    Immutable (its attributes are read-only); safe to share between threads. Pickles (for
    multiprocessing and Dask) as its source and options, loaded again where it is unpickled:
    the file (which must hold the same bytes there) or the text."""

    def __init__(self, core, scale=1.0):
        self._core = core
        self.scale = scale
        bodies = core.bodies
        self._root = bodies[0]
        self._bodies = bodies[1:]
        self.frame = core.frame
        self.nq, self.nv = core.nq, core.nv
        self.coordinate_names = tuple(core.coordinate_names)
        self.speed_names = tuple(core.speed_names)
        self.body_names = tuple(b["name"] for b in self._bodies)
        self.joint_names = tuple(b["joint"]["name"] for b in self._bodies)
        self.joint_types = tuple(b["joint"]["type"] for b in self._bodies)
        self.masses = np.array([b["mass"] for b in self._bodies], dtype=np.float64)
        self.mass_centers = np.array([b["mass_center"] for b in self._bodies],
                                     dtype=np.float64).reshape(-1, 3)
        self.lower = np.array(core.lower, dtype=np.int64)
        self._lower_table = None  # on first use: (depth + 1) x N entries, N^2 on a chain
        self.mimics = tuple(core.mimics)
        self.warnings = tuple(core.warnings)
        self.neutral_position = np.array(core.neutral_position, dtype=np.float64)
        self._body_index = {name: k for k, name in enumerate(self.body_names, 1)}
        self._coordinate_index = {n: i for i, n in enumerate(self.coordinate_names)}
        self._speed_index = {n: i for i, n in enumerate(self.speed_names)}
        self.masses, self.mass_centers, self.lower, self.neutral_position = (
            _frozen(a) for a in (self.masses, self.mass_centers, self.lower,
                                 self.neutral_position))
        self._source = None  # load()'s arguments, for pickle
        self._sealed = True

    def __setattr__(self, name, value):
        if self.__dict__.get("_sealed") and not name.startswith("_"):
            raise AttributeError("Model is immutable: %s cannot be set (load another model)"
                                 % name)
        object.__setattr__(self, name, value)

    def __delattr__(self, name):
        raise AttributeError("Model is immutable: %s cannot be deleted" % name)

    def __reduce__(self):
        if self._source is None:
            raise TypeError("a Model made without mb_kinematics.load cannot be pickled")
        return _load_pickled, self._source

    def __copy__(self):
        return self

    def __deepcopy__(self, memo):
        return self  # immutable: a copy would be the same model

    @property
    def body_count(self):
        """N, the number of bodies (R, the inertial frame, is not one)."""
        return len(self.body_names)

    @property
    def root(self):
        """bodies[0], R: a URDF's root link (its mass counts in the system quantities)."""
        return dict(self._root)

    @property
    def lower_table(self):
        """The lower body arrays L^t(k) (Table 4.2.1), (rows, N), made on first use: a chain of
        N bodies has N + 1 rows, so a model loaded only to compute never pays for them."""
        if self._lower_table is None:
            table = np.array(self._core.lower_table, dtype=np.int64)
            self._lower_table = _frozen(table.reshape(-1, len(self.lower)))
        return self._lower_table

    def tables(self):
        """The lower body arrays table (Table 4.2.1) as `mbk tables` prints it."""
        return self._core.tables_text

    def body_index(self, name):
        """k (1..N) of the body of that name; ValueError if there is none."""
        try:
            return self._body_index[name]
        except KeyError:
            raise ValueError("unknown body %r" % (name,)) from None

    def __repr__(self):
        return "<mb_kinematics.Model: %d bodies, nq=%d, nv=%d, frame %r>" % (
            self.body_count, self.nq, self.nv, self.frame)

    def read_recording(self, path, scale=None, joint_states="/joint_states",
                       joint_accelerations=None, base_odometry=None):
        """A rosbag (sensor_msgs/JointState on `joint_states`; with `joint_accelerations`,
        mb_kinematics_msgs/JointAccelerations on that topic; with `base_odometry`, the floating
        base's nav_msgs/Odometry on that topic, as `mbk bag --base-odometry`), a trajectory CSV
        (`time,<coordinate>,...`) or a BVH file's motion (this model being its skeleton) read as
        `mbk bag` reads it: a Recording. A BVH file's positions are read with the model's
        `scale`; a `scale` given and different from it is refused (ValueError)."""
        if isinstance(path, os.PathLike):
            path = os.fspath(path)
        if not isinstance(path, str):
            raise TypeError("path: a file name (str), not %s" % type(path).__name__)
        scale = _number(scale, "scale")
        if scale is not None and float(scale) != self.scale:
            raise ValueError("scale: %r, but the model was loaded with scale %r: a BVH file's "
                             "positions and its skeleton take one scale (leave scale out)"
                             % (scale, self.scale))
        topics = {"joint_states": joint_states, "joint_accelerations": joint_accelerations or "",
                  "base_odometry": base_odometry or ""}
        for name, topic in topics.items():
            if not isinstance(topic, str):
                raise TypeError("%s: a topic name (str), not %s" % (name, type(topic).__name__))
        core = _missing_file_checked(_core.read_recording, path, self._core, path, self.scale,
                                     topics["joint_states"], topics["joint_accelerations"],
                                     topics["base_odometry"])
        return Recording(core, (_read_pickled, (self, os.path.abspath(path), scale, joint_states,
                                                joint_accelerations, base_odometry)))

    def recording(self, times, positions):
        """A Recording of positions (N, nq) at increasing times (N,): every coordinate in every
        row."""
        times = np.ascontiguousarray(_real(times, "times"), dtype=np.float64)
        positions = _real(positions, "positions")
        if times.ndim != 1 or positions.shape != (len(times), self.nq):
            raise ValueError("times, positions: shapes %s, %s, expected (N,) and (N, %d)" %
                             (times.shape, positions.shape, self.nq))
        if not (np.isfinite(times).all() and np.isfinite(positions).all()):
            raise ValueError("times, positions: not finite (drop or repair those samples)")
        positions = np.array(positions, dtype=np.float64, order="C")  # the caller's may change
        times = times.copy()
        return Recording(_core.recording_of_positions(self._core, times, positions),
                         (_recording_pickled, (self, times, positions)))

    def states(self, recording, estimator="auto", max_gap=None):
        """Every row's joint state as `mbk bag` computes it: the recorded values, velocities and
        accelerations from the offline estimator where not recorded (`estimator` as
        `mbk bag --estimator`; `max_gap` seconds, default 5 x the median interval). A dict:
        `time`, `position`, `velocity`, `acceleration` (rows, nq), with "auto" `velocity_se`
        and `acceleration_se` (standard errors, 0 where recorded; a coordinate missing from a
        row has its last sample's), and `valid` (rows,): False where mbk bag drops the row (too
        few samples around it), whose `drop_reason` says why."""
        gap = _estimator_arguments(recording, estimator, max_gap)
        out = _core.recording_states(self._core, recording._core, estimator, gap)
        out["time"] = recording.times
        out["valid"] = np.array([not r for r in out["drop_reason"]], dtype=bool)
        return out

    def recording_kinematics(self, recording, estimator="auto", max_gap=None, **options):
        """What `mbk bag` does, in memory, by its own pipeline: the rows it writes (states() of
        the recording, less the rows it drops: too few samples around them, a state
        mbk::check_state refuses, kinematics not finite), then kinematics() of them (options as
        kinematics()). The dict of kinematics() plus `time`, the rows' states under
        `joint_position`, `joint_velocity`, `joint_acceleration`, and `drops` (rows dropped
        by reason, the reading's included).

        A recording with base odometry (read_recording's `base_odometry`): every body in R as
        `mbk bag --base-odometry` computes it, in the node's layout (body 1 the base, named
        in `body_names`): `time`, `rotation`, `origin`, `omega`, `alpha`, `mass_center`,
        `velocity`, `acceleration`, `system_mass_center`, `system_velocity`,
        `system_acceleration`, and `drops` (rows dropped by reason, the reading's included);
        options: `threads` only."""
        if isinstance(recording, Recording) and recording.base is not None:
            unknown = set(options) - {"threads"}
            if unknown:
                raise ValueError("with base odometry: %s not available (threads only)"
                                 % ", ".join(sorted(unknown)))
            gap = _estimator_arguments(recording, estimator, max_gap)
            return _core.floating_base_kinematics(self._core, recording._core, estimator, gap,
                                                  _threads(options.get("threads")))
        gap = _estimator_arguments(recording, estimator, max_gap)
        rows = _core.recording_rows(self._core, recording._core, estimator, gap,
                                    _threads(options.get("threads")))
        out = self.kinematics(rows["position"], rows["velocity"], rows["acceleration"],
                              **options)
        out["time"] = rows["time"]
        for name in ("position", "velocity", "acceleration"):
            out["joint_" + name] = rows[name]
        out["drops"] = rows["drops"]
        return out

    def kinematics(self, q, velocity=None, acceleration=None, outputs=None, bodies=None,
                   threads=None, out=None, dtype=np.float64):
        """Every body's kinematics for every sample, as a dict name -> numpy array.

        q: (nq,) or (N, nq) coordinates, or a dict coordinate name -> value or (N,) array
        (missing coordinates 0, Euler parameters the identity). velocity, acceleration: (nv,)
        or (N, nv), or a dict speed name -> values (missing speeds 0). Mimic coordinates are set
        from their sources. outputs: names from OUTPUTS (default: what the inputs allow, the
        partial velocities left out); bodies: names or indices 1..N (default all, in order);
        threads: default the machine's cores; out: dict name -> array to write into
        (C-contiguous, writeable, of `dtype` and the output's shape); dtype: float64 or float32.
        A (nq,) q gives arrays without the leading N axis."""
        single, q = _positions(self, q)
        if acceleration is not None and velocity is None:
            raise ValueError("acceleration: given without velocity (give zeros for a body at rest)")
        samples = q.shape[0]
        velocity = _speeds(self, velocity, "velocity", samples, single)
        acceleration = _speeds(self, acceleration, "acceleration", samples, single)
        dtype = _dtype(dtype)
        chosen = _bodies(self, bodies)
        names = _outputs(outputs, out, velocity is not None, acceleration is not None)
        arrays = {}
        for name in names:
            shape = _shape(self, name, samples, len(chosen))
            given = None if out is None else out.get(name)
            arrays[name] = (_core.empty(shape, dtype == np.float32) if given is None
                            else _out_array(given, name, shape[1:] if single else shape, dtype,
                                            shape))
        q, velocity, acceleration = _apart(arrays, q, velocity, acceleration)
        _core.batch_kinematics(self._core, q, velocity, acceleration, arrays, list(chosen),
                               _threads(threads), dtype == np.float32)
        if single:
            return {name: (out[name] if out is not None and name in out else a[0])
                    for name, a in arrays.items()}
        return arrays

    def kinematics_chunks(self, q, velocity=None, acceleration=None, rows=10000, out=None,
                          **options):
        """kinematics() of (N, nq) q (and (N, nv) velocity, acceleration) `rows` samples at a
        time, for any N in the memory of one chunk: yields (start, out) per chunk, out's arrays
        holding samples start.. start + len (rows, fewer in the last chunk). The arrays are
        reused by the next chunk: copy what must outlive it. out: dict name -> array of `rows`
        rows (as kinematics()' out= for `rows` samples) to write every chunk into; without it the
        first chunk allocates them. Options as kinematics()."""
        rows = _count(rows, "rows")
        single, q = _positions(self, q)
        if single:
            raise ValueError("q: shape (%d,), expected (N, %d) rows to split" % (self.nq, self.nq))
        if out is not None and not isinstance(out, dict):
            raise TypeError("out: a dict name -> array, not %s" % type(out).__name__)
        for name, a in (out or {}).items():
            if not isinstance(a, np.ndarray) or a.ndim == 0 or len(a) != rows:
                raise ValueError("out[%r]: %s, expected %d rows (rows=%d)" % (
                    name, "shape %s" % (a.shape,) if isinstance(a, np.ndarray) else
                    type(a).__name__, rows, rows))
        n = q.shape[0]
        velocity = _speeds(self, velocity, "velocity", n, False)
        acceleration = _speeds(self, acceleration, "acceleration", n, False)
        arrays = out
        for start in range(0, n, rows):
            stop = min(n, start + rows)
            part = [None if x is None else x[start:stop] for x in (velocity, acceleration)]
            given = None if arrays is None else {k: a[:stop - start] for k, a in arrays.items()}
            arrays = self.kinematics(q[start:stop], part[0], part[1], out=given, **options)
            yield start, arrays


def _frozen(array):
    """A read-only view of a read-only array: setflags(write=True) cannot undo it (numpy refuses
    to make a view writeable over a base that is not)."""
    array = np.array(array)  # owns its data: no writeable base behind it
    array.setflags(write=False)
    view = array.view()
    view.setflags(write=False)
    return view


def _read_pickled(model, path, scale, joint_states, joint_accelerations, base_odometry):
    """A pickled Recording read again from its file, with the same model and options."""
    return model.read_recording(path, scale, joint_states, joint_accelerations, base_odometry)


def _recording_pickled(model, times, positions):
    """A pickled Recording of arrays made again."""
    return model.recording(times, positions)


def _estimator_arguments(recording, estimator, max_gap):
    """Checks states()' arguments; the gap in seconds (0: the default)."""
    if not isinstance(recording, Recording):
        raise TypeError("recording: a Recording (read_recording or recording), not %s"
                        % type(recording).__name__)
    if not isinstance(estimator, str):
        raise TypeError("estimator: a name such as 'auto', not %s" % type(estimator).__name__)
    gap = 0.0 if max_gap is None else _number(max_gap, "max_gap")
    if max_gap is not None and not (gap > 0 and np.isfinite(gap)):
        raise ValueError("max_gap: %r, expected seconds above 0" % (max_gap,))
    return gap


def _number(value, name):
    """A real number as a float (None stays None); TypeError for another type, ValueError for
    one a double cannot hold."""
    if value is None:
        return None
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.number)):
        raise TypeError("%s: a number, not %s" % (name, type(value).__name__))
    try:
        return float(value)
    except OverflowError:
        raise ValueError("%s: %r is beyond a double's range" % (name, value)) from None


def _real(value, name):
    a = np.asarray(value)
    if a.dtype.kind not in "iuf":
        raise TypeError("%s: dtype %s, expected real numbers" % (name, a.dtype))
    return a


def _positions(model, q):
    if isinstance(q, dict):
        return _from_dict(model, q, "q", model._coordinate_index, model.neutral_position)
    a = _real(q, "q")
    if a.ndim not in (1, 2) or a.shape[-1] != model.nq:
        raise ValueError("q: shape %s, expected (%d,) or (N, %d)" % (a.shape, model.nq, model.nq))
    rows = a.reshape(1 if a.ndim == 1 else len(a), model.nq)  # -1 is unknown when nq is 0
    return a.ndim == 1, np.ascontiguousarray(rows, dtype=np.float64)


def _from_dict(model, values, name, index, neutral):
    columns, samples = {}, None
    for key, value in values.items():
        if key not in index:
            raise ValueError("%s: unknown name %r" % (name, key))
        a = _real(value, "%s[%r]" % (name, key))
        if a.ndim > 1 or (samples is not None and a.ndim == 1 and len(a) != samples) or (
                samples is not None and (a.ndim == 0) != (samples < 0)):
            raise ValueError("%s[%r]: shape %s, expected that of the other names'" %
                             (name, key, a.shape))
        samples = -1 if a.ndim == 0 else len(a)
        columns[index[key]] = a
    single = samples is None or samples < 0
    rows = np.tile(neutral, (1 if single else samples, 1))
    for i, a in columns.items():
        rows[:, i] = a
    return single, rows


def _speeds(model, value, name, samples, single):
    if value is None:
        return None
    if isinstance(value, dict):
        is_single, rows = _from_dict(model, value, name, model._speed_index, np.zeros(model.nv))
        if not value:
            return np.zeros((samples, model.nv))
        if is_single != single or rows.shape[0] != samples:
            raise ValueError("%s: %s, q has %s" % (name, "one sample" if is_single else
                             "%d samples" % rows.shape[0], "one" if single else samples))
        return rows
    a = _real(value, name)
    expected = (model.nv,) if single else (samples, model.nv)
    if a.shape != expected:
        raise ValueError("%s: shape %s, expected %s (as q)" % (name, a.shape, expected))
    return np.ascontiguousarray(a.reshape(samples, model.nv), dtype=np.float64)


def _dtype(dtype):
    try:
        d = np.dtype(dtype)
    except TypeError:
        raise TypeError("dtype: float64 or float32, not %r" % (dtype,)) from None
    if d not in (np.float64, np.float32):
        raise TypeError("dtype: float64 or float32, not %s" % d)
    return d


def _bodies(model, bodies):
    if bodies is None:
        return range(1, model.body_count + 1)
    if isinstance(bodies, (bool, np.bool_)):
        raise TypeError("bodies: body names or indices, not bool")
    if isinstance(bodies, (str, int, np.integer)):
        bodies = [bodies]
    chosen = []
    for b in bodies:
        if isinstance(b, str):
            if b not in model._body_index:
                raise ValueError("bodies: unknown body %r" % b)
            chosen.append(model._body_index[b])
            continue
        try:
            if isinstance(b, (bool, np.bool_)):
                raise TypeError
            k = operator.index(b)
        except TypeError:
            raise TypeError("bodies: a body name or index, not %s" % type(b).__name__) from None
        if not 1 <= k <= model.body_count:
            raise ValueError("bodies: index %d out of range 1..%d" % (k, model.body_count))
        chosen.append(k)
    return chosen


def _outputs(outputs, out, has_velocity, has_acceleration):
    if out is not None and not isinstance(out, dict):
        raise TypeError("out: a dict name -> array, not %s" % type(out).__name__)
    if outputs is None and out is not None:
        outputs = list(out)
    if outputs is None:
        level = _ACCELERATION if has_acceleration else _VELOCITY if has_velocity else _POSE
        return [n for n in OUTPUTS if n not in OPT_IN and _TRAITS[n]["level"] <= level]
    if isinstance(outputs, str):
        outputs = [outputs]
    names = []
    for name in outputs:
        if name not in _TRAITS:
            raise ValueError("outputs: unknown output %r (known: %s)" % (name, ", ".join(OUTPUTS)))
        if _TRAITS[name]["needs_velocity"] and not has_velocity:
            raise ValueError("outputs: %r needs velocity" % name)
        if _TRAITS[name]["needs_acceleration"] and not has_acceleration:
            raise ValueError("outputs: %r needs acceleration" % name)
        if name not in names:
            names.append(name)
    for name in out or {}:
        if name not in names:
            raise ValueError("out: %r is not among the outputs asked for" % (name,))
    return names


def _shape(model, name, samples, bodies):
    return _core.field_shape(model._core, name, samples, bodies)


def _out_array(a, name, shape, dtype, full):
    where = "out[%r]" % name
    if not isinstance(a, np.ndarray):
        raise TypeError("%s: a numpy array, not %s" % (where, type(a).__name__))
    if a.dtype != dtype:
        raise TypeError("%s: dtype %s, expected %s" % (where, a.dtype, dtype))
    if a.shape != shape:
        raise ValueError("%s: shape %s, expected %s" % (where, a.shape, shape))
    if not a.flags.c_contiguous:
        raise ValueError("%s: not C-contiguous" % where)
    if not a.flags.writeable:
        raise ValueError("%s: read-only" % where)
    return a.reshape(full)


def _apart(arrays, *inputs):
    """The inputs, each copied where an output array overlaps it (numpy's ufuncs do the same);
    ValueError for two outputs that overlap (each would be written over the other's values).
    Every array here is C-contiguous: overlapping bounds are overlapping elements."""
    names = list(arrays)
    for i, name in enumerate(names):
        for other in names[i + 1:]:
            if np.may_share_memory(arrays[name], arrays[other]):
                raise ValueError("out[%r] and out[%r]: overlap in memory" % (name, other))
    return [None if a is None else
            a.copy() if any(np.may_share_memory(a, o) for o in arrays.values()) else a
            for a in inputs]


def _count(value, name):
    """A count of at least 1 (ValueError naming `name` otherwise)."""
    try:
        n = operator.index(value)
    except TypeError:
        raise TypeError("%s: an integer, not %s" % (name, type(value).__name__)) from None
    if n < 1:
        raise ValueError("%s: %d, expected at least 1" % (name, n))
    return n


def _threads(threads):
    if threads is None:
        return 0
    try:
        if isinstance(threads, (bool, np.bool_)):
            raise TypeError
        n = operator.index(threads)
    except TypeError:
        raise TypeError("threads: an integer, not %s" % type(threads).__name__) from None
    if not 1 <= n <= MOST_THREADS:
        raise ValueError("threads: %d, expected 1 to %d" % (n, MOST_THREADS))
    return n
