"""The filter objects: one class per kind over the C API's opaque handle."""

from __future__ import annotations

import ctypes
from ctypes import POINTER, byref, c_double, c_int32, c_size_t, c_uint8, c_uint32, c_void_p
from dataclasses import dataclass
from typing import Any, ClassVar, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import _native as n
from ._native import Frame, Init, Kind, Status, lib

ArrayLike = Union[np.ndarray, Sequence[float], Sequence[Sequence[float]], float]


class OrientError(Exception):
    """A call the library refused. It changed nothing (a batch keeps the samples before
    ``index``).

    Attributes:
        status: the library's :class:`Status`.
        message: the library's detail (``orient_last_error``), or the fixed message of
            the status when there is no detail.
        index: for a batch, the index of the sample that was refused; else ``None``.
    """

    def __init__(self, status: int, message: str, index: Optional[int] = None) -> None:
        self.status = Status(status)
        self.message = message
        self.index = index
        super().__init__(f"{self.status.name}: {message}")


def status_message(status: int) -> str:
    """The library's fixed English message for a status code."""
    return lib.orient_status_message(int(status)).decode()


def _check(status: int, index: Optional[int] = None) -> None:
    if status != Status.OK:
        detail = lib.orient_last_error().decode() or status_message(status)
        raise OrientError(status, detail, index)


def version() -> str:
    """The loaded library's version, e.g. ``"0.1.0"``."""
    return lib.orient_version().decode()


@dataclass(frozen=True)
class ParamInfo:
    """One setting as the library's parameter table describes it (``orient_param_info``)."""

    name: str
    id: int
    unit: str
    description: str
    default: float
    #: Smallest accepted value, besides 0 where ``zero_off``.
    min: float
    max: float
    #: 0 is also accepted and turns the feature off.
    zero_off: bool


KIND_NAMES: Dict[str, Kind] = {k.name.lower(): k for k in Kind}
FRAME_NAMES: Dict[str, Frame] = {f.name.lower(): f for f in Frame}


def _kind(kind: Union[str, int, Kind]) -> Kind:
    if isinstance(kind, str):
        try:
            return KIND_NAMES[kind.lower()]
        except KeyError:
            raise OrientError(
                Status.INVALID_ARGUMENT, f"unknown filter kind '{kind}' (one of: {', '.join(KIND_NAMES)})"
            ) from None
    try:
        return Kind(int(kind))
    except ValueError:
        raise OrientError(Status.INVALID_ARGUMENT, f"unknown filter kind {kind}") from None


def params(kind: Union[str, int, Kind]) -> List[ParamInfo]:
    """The settings of a kind (common ones first), read from the library's table."""
    k = _kind(kind)
    count = c_uint32()
    _check(lib.orient_param_count(k, byref(count)))
    out = []
    for i in range(count.value):
        info = n.OrientParamInfo()
        _check(lib.orient_param_info(k, i, byref(info)))
        out.append(_param_info(info))
    return out


def _param_info(info: n.OrientParamInfo) -> ParamInfo:
    """A parameter as the library describes it."""
    return ParamInfo(
        name=info.name.decode(),
        id=info.id,
        unit=info.unit.decode(),
        description=info.description.decode(),
        default=info.default_value,
        min=info.min,
        max=info.max,
        zero_off=bool(info.flags & n.PARAM_FLAG_ZERO_OFF),
    )


def _param_id(kind: Kind, name: str) -> int:
    pid = c_uint32()
    _check(lib.orient_param_find(kind, name.encode(), byref(pid)))
    return pid.value


def _rows(x: Any, what: str, n: Optional[int] = None) -> np.ndarray:
    """``x`` as a C-contiguous float64 (N, 3) array; the same object when it already is one."""
    a = np.ascontiguousarray(x, dtype=np.float64)
    if a.ndim != 2 or a.shape[1] != 3 or (n is not None and a.shape[0] != n):
        want = f"({n}, 3)" if n is not None else "(N, 3)"
        raise ValueError(f"{what} must have shape {want}, got {a.shape}")
    return a


def _vec3(v: Any, what: str) -> n.OrientVec3:
    a = np.asarray(v, dtype=np.float64)
    if a.shape != (3,):
        raise ValueError(f"{what} must have 3 values, got shape {a.shape}")
    return n.OrientVec3(float(a[0]), float(a[1]), float(a[2]))


def _ptr(a: Optional[np.ndarray], ctype: Any, offset_rows: int = 0) -> Any:
    """A ``ctype *`` to row ``offset_rows`` of ``a`` (NULL for None), for the typed pointer
    parameters of _native's prototypes."""
    if a is None:
        return None
    address = a.ctypes.data + offset_rows * a.strides[0] if a.ndim else a.ctypes.data
    return ctypes.cast(address, POINTER(ctype))


def _record_dtype(struct: Any) -> np.dtype:
    """A ctypes struct of numbers, arrays of numbers and OrientVec3 as a NumPy record of
    the same layout (an OrientVec3 as three float64)."""
    fields: List[Any] = []
    for name, ctype in struct._fields_:
        if ctype is n.OrientVec3:
            fields.append((name, "=f8", (3,)))
        elif issubclass(ctype, ctypes.Array):
            fields.append((name, np.dtype(ctype._type_), (ctype._length_,)))
        else:
            fields.append((name, np.dtype(ctype)))
    dtype = np.dtype(fields)
    assert dtype.itemsize == ctypes.sizeof(struct), struct
    assert all(dtype.fields[f][1] == getattr(struct, f).offset for f in dtype.names), struct
    return dtype


#: OrientDiagnostics as a NumPy record: update_batch fills an array of these in place.
DIAGNOSTICS_DTYPE = _record_dtype(n.OrientDiagnostics)


@dataclass
class BatchResult:
    """What :meth:`Filter.update_batch` returns, one row per sample.

    Attributes:
        quaternion: (N, 4) float64, w, x, y, z after each sample (configured frame).
        flags: (N,) uint32, ``FLAG_*`` bits after each sample.
        diagnostics: (N,) records of :data:`DIAGNOSTICS_DTYPE` (``gyro_bias`` (N, 3),
            ``rest``, ``alpha``, ``mu_ka``, ``mu_km``, ``mu_k``, ``rate`` (N, 3),
            ``covariance`` (N, 10), ``present``); a field the kind does not report is NaN.
        status: (N,) int32, 0 for an accepted sample, else the :class:`Status` that
            refused it (only with ``errors="skip"``; the row then repeats the outputs
            from before it).
    """

    quaternion: np.ndarray
    flags: np.ndarray
    diagnostics: np.ndarray
    status: np.ndarray

    @property
    def accel_used(self) -> np.ndarray:
        """(N,) bool: the sample's update used the accelerometer."""
        return (self.flags & n.FLAG_ACCEL_USED) != 0

    @property
    def mag_used(self) -> np.ndarray:
        """(N,) bool: the sample's update used the magnetometer."""
        return (self.flags & n.FLAG_MAG_USED) != 0

    @property
    def gap(self) -> np.ndarray:
        """(N,) bool: the sample followed a gap (dt above ``gap_dt``)."""
        return (self.flags & n.FLAG_GAP) != 0

    @property
    def rest(self) -> np.ndarray:
        """(N,) bool: the filter reported rest (kinds with a rest detector; else all False)."""
        return self.diagnostics["rest"] == 1.0


def smooth(
    gyr: ArrayLike,
    acc: Optional[ArrayLike] = None,
    mag: Optional[ArrayLike] = None,
    *,
    dt: ArrayLike,
) -> np.ndarray:
    """Offline mode with the offline defaults (``orient_smooth_config_default``: the
    recommended kind, heading time constant 27 s): the whole recording smoothed forward
    and backward. Arguments and result as :meth:`Filter.smooth`."""
    f = Robust()
    _check(lib.orient_smooth_config_default(byref(f._config)))
    return f.smooth(gyr, acc, mag, dt=dt)


def smooth_memory(count: int) -> int:
    """Bytes the library may allocate while smoothing ``count`` samples
    (``orient_smooth_memory``): 8 per sample plus 32768, whatever the kind, besides the
    (count, 4) result. Raises OrientError (COUNT_TOO_LARGE) above PTRDIFF_MAX / 32."""
    out = c_size_t()
    _check(lib.orient_smooth_memory(count, byref(out)))
    return out.value


class Filter:
    """An orientation filter. Use a kind's class (:class:`Madgwick`, :class:`Robust`, ...)
    or ``Filter("robust", ...)``.

    Args:
        kind: only for ``Filter`` itself: a kind name (``"madgwick"``, ``"mahony"``,
            ``"complementary"``, ``"ekf"``, ``"gmvdk"``, ``"robust"``) or :class:`Kind`.
        frame: earth frame of every output: ``"enu"`` (default), ``"ned"`` or ``"nwu"``.
        initial: ``None`` (default: from the first accelerometer/magnetometer sample),
            ``"identity"``, or a quaternion (w, x, y, z) in the configured frame.
        for_joints: the settings a sensor's filter runs with under :class:`Joints`
            (``orient_config_for_joints``, whose doc in orient.h gives each value and why;
            ``Robust(for_joints=True)[name]`` reads them: for the recommended kind a faster
            bias random walk and a wider motion bias bound and rest threshold; other kinds
            unchanged), before
            ``settings``.
        **settings: parameters by name (see :meth:`params`); each is checked against
            the library's range.

    Raises:
        OrientError: an unknown setting (``UNKNOWN_PARAM``), a value out of range
            (``PARAM_OUT_OF_RANGE``), an unknown kind or frame (``INVALID_ARGUMENT``).

    A filter must not be used from two threads at once; distinct filters are independent.
    """

    KIND: ClassVar[Optional[Kind]] = None

    def __init__(
        self,
        kind: Union[str, int, Kind, None] = None,
        *,
        frame: str = "enu",
        initial: Union[None, str, Sequence[float], np.ndarray] = None,
        for_joints: bool = False,
        **settings: float,
    ) -> None:
        self._handle: Optional[int] = None
        if self.KIND is not None:
            if kind is not None:
                raise TypeError(f"{type(self).__name__} takes no kind argument")
            k = self.KIND
        elif kind is None:
            raise TypeError("Filter needs a kind, e.g. Filter('robust'), or use a kind's class")
        else:
            k = _kind(kind)
        config = n.OrientConfig()
        _check(lib.orient_config_default(k, byref(config)))
        try:
            config.frame = FRAME_NAMES[frame.lower()]
        except (KeyError, AttributeError):
            raise OrientError(Status.INVALID_ARGUMENT, f"unknown frame '{frame}' (enu, ned, nwu)") from None
        if initial is None:
            config.init = Init.ACC_MAG
        elif isinstance(initial, str):
            if initial != "identity":
                raise OrientError(Status.INVALID_ARGUMENT, "initial must be None, 'identity' or (w, x, y, z)")
            config.init = Init.IDENTITY
        else:
            q = np.asarray(initial, dtype=np.float64)
            if q.shape != (4,):
                raise ValueError(f"initial must be (w, x, y, z), got shape {q.shape}")
            config.init = Init.GIVEN
            config.initial = n.OrientQuaternion(*map(float, q))
        if for_joints:
            _check(lib.orient_config_for_joints(byref(config)))
        for name, value in settings.items():
            try:
                _check(lib.orient_config_set_param(byref(config), _param_id(k, name), float(value)))
            except OrientError as e:
                raise OrientError(e.status, f"{k.name.lower()} setting '{name}': {e.message}") from None
        self._config = config
        handle = c_void_p()
        _check(lib.orient_filter_new(byref(config), byref(handle)))
        self._handle = handle.value
        self._kind_value = k

    # -- lifecycle ---------------------------------------------------------------------

    def close(self) -> None:
        """Releases the native filter now (also done when the object is collected)."""
        if self._handle is not None:
            lib.orient_filter_free(self._handle)
            self._handle = None

    def __del__(self) -> None:
        self.close()

    def __enter__(self) -> "Filter":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()

    @property
    def _h(self) -> int:
        if self._handle is None:
            raise OrientError(Status.INVALID_HANDLE, "the filter was closed")
        return self._handle

    def __repr__(self) -> str:
        return f"<orient.{type(self).__name__} kind={self.kind!r}>"

    # -- settings ----------------------------------------------------------------------

    @property
    def kind(self) -> str:
        """The kind's name, e.g. ``"robust"``."""
        k = c_int32()
        _check(lib.orient_filter_kind(self._h, byref(k)))
        return Kind(k.value).name.lower()

    @classmethod
    def params(cls, kind: Union[str, int, Kind, None] = None) -> List[ParamInfo]:
        """The settings of this kind, from the library's parameter table."""
        k = cls.KIND if cls.KIND is not None else kind
        if k is None:
            raise TypeError("Filter.params needs a kind")
        return params(k)

    def __getitem__(self, name: str) -> float:
        """The current value of a setting, by name."""
        v = c_double()
        _check(lib.orient_filter_get_param(self._h, _param_id(self._kind_value, name), byref(v)))
        return v.value

    def __setitem__(self, name: str, value: float) -> None:
        """Changes a setting of the running filter (range-checked); the orientation is kept."""
        _check(lib.orient_filter_set_param(self._h, _param_id(self._kind_value, name), float(value)))

    # -- updates -----------------------------------------------------------------------

    def update(self, gyr: ArrayLike, acc: Optional[ArrayLike] = None, mag: Optional[ArrayLike] = None, *, dt: float) -> np.ndarray:
        """One sample: gyroscope (rad/s), accelerometer (m/s^2) and magnetometer (any
        unit) as 3 values each, ``acc`` and ``mag`` optional; ``dt`` in seconds.

        Returns the orientation after it, (4,) float64 w, x, y, z.

        Raises:
            OrientError: a refused sample (NaN or Inf, bad dt, zero or huge vector,
                saturated reading, not initialised); the filter is unchanged.
        """
        s = n.OrientSample()
        s.dt = float(dt)
        s.gyro = _vec3(gyr, "gyr")
        s.flags = n.SAMPLE_GYRO
        if acc is not None:
            s.accel = _vec3(acc, "acc")
            s.flags |= n.SAMPLE_ACCEL
        if mag is not None:
            s.mag = _vec3(mag, "mag")
            s.flags |= n.SAMPLE_MAG
        _check(lib.orient_filter_update(self._h, byref(s)))
        return self.quaternion

    def update_batch(
        self,
        gyr: ArrayLike,
        acc: Optional[ArrayLike] = None,
        mag: Optional[ArrayLike] = None,
        *,
        dt: ArrayLike,
        errors: str = "raise",
    ) -> BatchResult:
        """Many samples in one native call (``orient_filter_update_arrays``).

        Args:
            gyr: (N, 3) rad/s. ``acc`` (N, 3) m/s^2 and ``mag`` (N, 3) are optional.
                C-contiguous float64 arrays are read in place, not copied; anything
                else is converted once.
            dt: seconds, one value for every sample or (N,) one per sample.
            errors: ``"raise"`` (default): stop at the first refused sample and raise
                :class:`OrientError` with its ``index`` (the samples before it stay
                applied). ``"skip"``: leave refused samples out and go on, as the replay
                tool does; their rows in ``status`` say why.

        Returns:
            :class:`BatchResult` with the quaternions, flags and diagnostics after each sample.
        """
        if errors not in ("raise", "skip"):
            raise ValueError("errors must be 'raise' or 'skip'")
        g = _rows(gyr, "gyr")
        count = g.shape[0]
        a = None if acc is None else _rows(acc, "acc", count)
        m = None if mag is None else _rows(mag, "mag", count)
        d = np.ascontiguousarray(dt, dtype=np.float64)
        if d.ndim == 0:
            d = d.reshape(1)
        if d.shape not in ((1,), (count,)):
            raise ValueError(f"dt must be one value or shape ({count},), got {d.shape}")
        per_sample_dt = d.shape[0] == count and count != 1
        q = np.empty((count, 4), dtype=np.float64)
        flags = np.empty(count, dtype=np.uint32)
        diag = np.empty(count, dtype=DIAGNOSTICS_DTYPE)
        status = np.zeros(count, dtype=np.int32)
        start = 0
        processed = c_size_t()
        h = self._h
        while True:
            rest = count - start
            st = lib.orient_filter_update_arrays(
                h,
                rest,
                _ptr(d, c_double, start if per_sample_dt else 0),
                rest if per_sample_dt else 1,
                _ptr(g, c_double, start),
                _ptr(a, c_double, start),
                _ptr(m, c_double, start),
                _ptr(q, n.OrientQuaternion, start),
                _ptr(flags, c_uint32, start),
                _ptr(diag, n.OrientDiagnostics, start),
                byref(processed),
            )
            if st == Status.OK:
                return BatchResult(q, flags, diag, status)
            bad = start + processed.value
            if errors == "raise":
                _check(st, bad)
            # A refused sample changes nothing: its row repeats the filter's outputs.
            status[bad] = st
            q[bad] = self.quaternion
            flags[bad] = self.flags
            lib.orient_filter_diagnostics(h, _ptr(diag, n.OrientDiagnostics, bad))
            start = bad + 1
            if start == count:
                return BatchResult(q, flags, diag, status)

    def smooth(
        self,
        gyr: ArrayLike,
        acc: Optional[ArrayLike] = None,
        mag: Optional[ArrayLike] = None,
        *,
        dt: ArrayLike,
    ) -> np.ndarray:
        """Offline mode (``orient_smooth_arrays``): the whole recording smoothed
        forward and backward with this filter's kind, frame and settings; every output
        uses the samples before and after it. This filter's own state is not used or
        changed.

        Args: as :meth:`update_arrays`.

        Returns:
            (N, 4) w, x, y, z at every sample.

        Raises:
            OrientError: at the first sample a forward run would refuse, with its ``index``;
                OUT_OF_MEMORY when the library's buffer (:func:`smooth_memory`) cannot
                be allocated.
        """
        g = _rows(gyr, "gyr")
        count = g.shape[0]
        a = None if acc is None else _rows(acc, "acc", count)
        m = None if mag is None else _rows(mag, "mag", count)
        d = np.ascontiguousarray(dt, dtype=np.float64)
        if d.ndim == 0:
            d = d.reshape(1)
        if d.shape not in ((1,), (count,)):
            raise ValueError(f"dt must be one value or shape ({count},), got {d.shape}")
        q = np.empty((count, 4), dtype=np.float64)
        processed = c_size_t()
        st = lib.orient_smooth_arrays(
            byref(self._config),
            count,
            _ptr(d, c_double),
            d.shape[0],
            _ptr(g, c_double),
            _ptr(a, c_double),
            _ptr(m, c_double),
            _ptr(q, n.OrientQuaternion),
            byref(processed),
        )
        if st != Status.OK:
            _check(st, processed.value)
        return q

    # -- outputs -----------------------------------------------------------------------

    @property
    def quaternion(self) -> np.ndarray:
        """(4,) w, x, y, z: sensor to earth in the configured frame (identity before
        initialisation)."""
        q = n.OrientQuaternion()
        _check(lib.orient_filter_quaternion(self._h, byref(q)))
        return np.array([q.w, q.x, q.y, q.z])

    @property
    def euler(self) -> Tuple[float, float, float]:
        """(yaw, pitch, roll) in radians, intrinsic Z-Y'-X''."""
        e = n.OrientEuler()
        _check(lib.orient_filter_euler(self._h, byref(e)))
        return (e.yaw, e.pitch, e.roll)

    @property
    def rotation_matrix(self) -> np.ndarray:
        """(3, 3) R with v_earth = R @ v_sensor."""
        m = (c_double * 9)()
        _check(lib.orient_filter_rotation_matrix(self._h, m))
        return np.array(m[:]).reshape(3, 3)

    def _vec_output(self, fn: Any) -> np.ndarray:
        v = n.OrientVec3()
        _check(fn(self._h, byref(v)))
        return np.array([v.x, v.y, v.z])

    @property
    def gravity(self) -> np.ndarray:
        """(3,) what the accelerometer reads at rest now, sensor frame, m/s^2."""
        return self._vec_output(lib.orient_filter_gravity)

    @property
    def linear_accel(self) -> np.ndarray:
        """(3,) last accelerometer reading minus gravity, sensor frame, m/s^2.

        Raises OrientError (NO_DATA) before the first accelerometer reading."""
        return self._vec_output(lib.orient_filter_linear_accel)

    @property
    def linear_accel_earth(self) -> np.ndarray:
        """(3,) :attr:`linear_accel` in the earth frame, m/s^2."""
        return self._vec_output(lib.orient_filter_linear_accel_earth)

    @property
    def flags(self) -> int:
        """``FLAG_*`` bits of the filter's state."""
        f = c_uint32()
        _check(lib.orient_filter_flags(self._h, byref(f)))
        return f.value

    @property
    def diagnostics(self) -> Dict[str, Any]:
        """The kind's internal states that hold values now, by name (``gyro_bias``,
        ``rest``, ``alpha``, ``mu_ka``, ``mu_km``, ``mu_k``, ``rate``, ``covariance``)."""
        d = np.empty(1, dtype=DIAGNOSTICS_DTYPE)
        _check(lib.orient_filter_diagnostics(self._h, _ptr(d, n.OrientDiagnostics)))
        present = int(d["present"][0])
        bits = [
            ("gyro_bias", n.DIAG_GYRO_BIAS),
            ("rest", n.DIAG_REST),
            ("alpha", n.DIAG_ALPHA),
            ("mu_ka", n.DIAG_MU_KA),
            ("mu_km", n.DIAG_MU_KM),
            ("mu_k", n.DIAG_MU_K),
            ("rate", n.DIAG_RATE),
            ("covariance", n.DIAG_COVARIANCE),
        ]
        out: Dict[str, Any] = {}
        for name, bit in bits:
            if present & bit:
                v = d[name][0]
                out[name] = float(v) if np.ndim(v) == 0 else np.array(v)
        return out

    @property
    def uncertainty(self) -> Dict[str, float]:
        """One standard deviation (rad) of the orientation's error where the kind models
        it, by name: ``heading`` (EKF and robust; the robust kind's grows while the
        magnetometer is distrusted or absent) and ``inclination`` (EKF). Empty for the
        other kinds and before initialisation."""
        u = n.OrientUncertainty()
        _check(lib.orient_filter_uncertainty(self._h, byref(u)))
        out: Dict[str, float] = {}
        if u.present & n.UNCERTAINTY_HEADING:
            out["heading"] = u.heading
        if u.present & n.UNCERTAINTY_INCLINATION:
            out["inclination"] = u.inclination
        return out

    # -- state -------------------------------------------------------------------------

    @property
    def state_size(self) -> int:
        """Size in bytes of :meth:`save`'s blob (constant per kind)."""
        size = c_size_t()
        _check(lib.orient_filter_state_size(self._h, byref(size)))
        return size.value

    def save(self) -> bytes:
        """The configuration and the whole state as a versioned, checksummed blob; a filter
        that loads it continues bit for bit as this one would."""
        size = self.state_size
        buf = (c_uint8 * size)()
        written = c_size_t()
        _check(lib.orient_filter_save(self._h, buf, size, byref(written)))
        return bytes(buf[: written.value])

    def load(self, blob: bytes) -> None:
        """Restores a blob from :meth:`save` of a filter of the same kind.

        Raises OrientError (INVALID_STATE) for a truncated, corrupted, foreign-kind or
        foreign-version blob; the filter is unchanged."""
        data = bytes(blob)
        buf = (c_uint8 * max(len(data), 1)).from_buffer_copy(data or b"\0")
        _check(lib.orient_filter_load(self._h, buf, len(data)))

    def reset(self) -> None:
        """Back to the state right after creation; settings changed since are kept."""
        _check(lib.orient_filter_reset(self._h))

    def set_quaternion(self, q: ArrayLike) -> None:
        """Sets the orientation (w, x, y, z, configured frame; normalised).

        Raises OrientError (NON_FINITE, ZERO_VECTOR, TOO_LARGE) for an unusable one."""
        a = np.asarray(q, dtype=np.float64)
        if a.shape != (4,):
            raise ValueError(f"a quaternion has 4 values, got shape {a.shape}")
        _check(lib.orient_filter_set_quaternion(self._h, byref(n.OrientQuaternion(*map(float, a)))))

    # -- mounting and heading (issue 20) -------------------------------------------------

    @property
    def mounting(self) -> np.ndarray:
        """(4,) w, x, y, z: sensor to segment (v_segment = m v_sensor); identity unless
        set. Setting it makes quaternion, euler and rotation_matrix the segment's; it is
        kept by reset() and saved by save()."""
        q = n.OrientQuaternion()
        _check(lib.orient_filter_mounting(self._h, byref(q)))
        return np.array([q.w, q.x, q.y, q.z])

    @mounting.setter
    def mounting(self, m: ArrayLike) -> None:
        _check(lib.orient_filter_set_mounting(self._h, byref(_quat(m))))

    @property
    def sensor_quaternion(self) -> np.ndarray:
        """(4,) the sensor's own orientation: heading offset and declination applied,
        the mounting not."""
        q = n.OrientQuaternion()
        _check(lib.orient_filter_sensor_quaternion(self._h, byref(q)))
        return np.array([q.w, q.x, q.y, q.z])

    def set_heading(self, yaw: float) -> None:
        """Turns the outputs about the vertical so that euler's yaw becomes `yaw` (rad);
        the inclination is kept. OrientError NOT_INITIALIZED before initialisation."""
        _check(lib.orient_filter_set_heading(self._h, float(yaw)))

    def reset_heading(self) -> None:
        """set_heading(0)."""
        _check(lib.orient_filter_reset_heading(self._h))

    @property
    def heading_offset(self) -> float:
        """The heading offset (rad) kept by set_heading() and the rig calls."""
        v = c_double()
        _check(lib.orient_filter_heading_offset(self._h, byref(v)))
        return v.value

    @property
    def declination(self) -> float:
        """Magnetic declination (rad, east positive, within [-pi, pi]); 0 unless set."""
        v = c_double()
        _check(lib.orient_filter_declination(self._h, byref(v)))
        return v.value

    @declination.setter
    def declination(self, value: float) -> None:
        _check(lib.orient_filter_set_declination(self._h, float(value)))

    # -- sensor calibration (issue 20) ---------------------------------------------------

    def set_sensor_model(self, sensor: str, matrix: Optional[ArrayLike] = None, offset: ArrayLike = (0.0, 0.0, 0.0)) -> None:
        """Sets the model applied to one sensor's readings ("gyro", "accel", "mag") before
        every update: calibrated = matrix @ (raw - offset). matrix None clears it."""
        sid = _SENSORS[sensor]
        if matrix is None:
            _check(lib.orient_filter_set_sensor_model(self._h, sid, None))
            return
        _check(lib.orient_filter_set_sensor_model(self._h, sid, byref(_model(matrix, offset))))

    def sensor_model(self, sensor: str) -> Optional[Tuple[np.ndarray, np.ndarray]]:
        """(matrix (3, 3), offset (3,)) of the sensor's model, or None when none is set."""
        m = n.OrientSensorModel()
        status = lib.orient_filter_sensor_model(self._h, _SENSORS[sensor], byref(m))
        if status == Status.NO_DATA:
            return None
        _check(status)
        return np.array(m.matrix[:]).reshape(3, 3), np.array([m.offset.x, m.offset.y, m.offset.z])


_SENSORS = {"gyro": n.SENSOR_GYRO, "accel": n.SENSOR_ACCEL, "mag": n.SENSOR_MAG}


def _model(matrix: ArrayLike, offset: ArrayLike) -> n.OrientSensorModel:
    m = np.asarray(matrix, dtype=np.float64)
    o = np.asarray(offset, dtype=np.float64)
    if m.shape != (3, 3) or o.shape != (3,):
        raise ValueError("a sensor model is a (3, 3) matrix and a (3,) offset")
    return n.OrientSensorModel((c_double * 9)(*m.ravel().tolist()), n.OrientVec3(*o.tolist()))


@dataclass
class MagFit:
    """What MagCalibrator.solve() found: calibrated = soft_iron @ (raw - hard_iron)."""

    soft_iron: np.ndarray
    hard_iron: np.ndarray
    field: float
    residual: float
    coverage: float
    samples: int
    trustworthy: bool


class MagCalibrator:
    """Magnetometer calibration (ellipsoid fit): add() readings while rotating the sensor
    over the sphere (no allocation per reading in the library), then solve()."""

    def __init__(self) -> None:
        self._state = n.OrientMagCalibrator()
        _check(lib.orient_mag_calibrator_init(byref(self._state)))

    def add(self, mag: ArrayLike) -> None:
        for row in np.atleast_2d(np.asarray(mag, dtype=np.float64)):
            _check(lib.orient_mag_calibrator_add(byref(self._state), byref(n.OrientVec3(*row.tolist()))))

    def solve(self) -> Optional[MagFit]:
        """The fit, or None while the readings do not determine an ellipsoid."""
        f = n.OrientMagFit()
        status = lib.orient_mag_calibrator_solve(byref(self._state), byref(f))
        if status == Status.NO_DATA:
            return None
        _check(status)
        o = f.model.offset
        return MagFit(np.array(f.model.matrix[:]).reshape(3, 3), np.array([o.x, o.y, o.z]), f.field, f.residual,
                      f.coverage, f.samples, bool(f.trustworthy))


def gyro_offset(still: ArrayLike) -> Tuple[np.ndarray, float]:
    """The gyroscope offset (mean, rad/s) of readings (n, 3) taken while still, and their
    RMS spread; pass the offset to set_sensor_model("gyro", np.eye(3), offset)."""
    a = np.ascontiguousarray(np.atleast_2d(np.asarray(still, dtype=np.float64)))
    rows = (n.OrientVec3 * len(a))(*[n.OrientVec3(*r.tolist()) for r in a])
    m = n.OrientSensorModel()
    spread = c_double()
    _check(lib.orient_gyro_offset(rows, len(a), byref(m), byref(spread)))
    return np.array([m.offset.x, m.offset.y, m.offset.z]), spread.value


def _quat(q: ArrayLike) -> n.OrientQuaternion:
    a = np.asarray(q, dtype=np.float64)
    if a.shape != (4,):
        raise ValueError(f"a quaternion has 4 values, got shape {a.shape}")
    return n.OrientQuaternion(*map(float, a))


def _rig_args(filters: Sequence[Filter], references: ArrayLike) -> Tuple[Any, Any, int]:
    refs = np.asarray(references, dtype=np.float64)
    if refs.shape != (len(filters), 4):
        raise ValueError(f"references must have shape ({len(filters)}, 4), got {refs.shape}")
    handles = (c_void_p * len(filters))(*[f._h for f in filters])
    quats = (n.OrientQuaternion * len(filters))(*[n.OrientQuaternion(*map(float, r)) for r in refs])
    return handles, quats, len(filters)


def calibrate_rig(filters: Sequence[Filter], references: ArrayLike, heading: Optional[float] = None) -> None:
    """Rig calibration from a reference posture: while the segments hold `references`
    ((n, 4) w, x, y, z, segment to posture frame), sets a common heading offset and every
    mounting so that filters[i] reads references[i] now and its segment afterwards.
    `heading` is the posture frame's yaw in the filters' earth frame (rad); None
    estimates it from the rig. The filters share one earth frame (a magnetometer); 6D
    rigs take calibrate_rig_each."""
    h, q, count = _rig_args(filters, references)
    _check(lib.orient_rig_calibrate(h, q, count, float("nan") if heading is None else float(heading)))


def calibrate_rig_each(filters: Sequence[Filter], references: ArrayLike) -> None:
    """Rig calibration of 6D filters, each heading its own (orient_rig_calibrate_each):
    each sensor taken as strapped along its segment, each mounting is its tilt there and
    each heading offset its own."""
    h, q, count = _rig_args(filters, references)
    _check(lib.orient_rig_calibrate_each(h, q, count))


def align_rig_heading(filters: Sequence[Filter], references: ArrayLike) -> None:
    """Heading-only alignment to the reference posture; mountings are kept."""
    h, q, count = _rig_args(filters, references)
    _check(lib.orient_rig_align_heading(h, q, count))


class Madgwick(Filter):
    """Madgwick 2010 gradient descent, IMU and MARG."""

    KIND = Kind.MADGWICK


class Mahony(Filter):
    """Mahony nonlinear complementary filter, optional bias integrator."""

    KIND = Kind.MAHONY


class Complementary(Filter):
    """McGinnis 2014 PI complementary filter: gains at rest only, start-up period (IMU)."""

    KIND = Kind.COMPLEMENTARY


class Ekf(Filter):
    """Kim & Golnaraghi 2004 quaternion EKF [q, omega, drift], magnetometer heading update."""

    KIND = Kind.EKF


class Gmvdk(Filter):
    """GMVDK 2024 double-SLERP filter with accelerometer trust alpha and magnetometer trust mu_K."""

    KIND = Kind.GMVDK


class Robust(Filter):
    """orient's recommended kind: accelerometer low-passed in a gyro-following frame, gyro
    bias learned at rest and in motion, magnetometer used only while undisturbed, attached
    magnets compensated."""

    KIND = Kind.ROBUST
