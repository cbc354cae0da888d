"""A rig's joints (``orient_joints_*``): each child segment held to its parent without a
magnetometer, and a whole rig recording in one call."""

from __future__ import annotations

import ctypes
import math
from ctypes import byref, c_double, c_size_t, c_uint8, c_uint32, c_void_p
from dataclasses import dataclass
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _native as n
from ._filter import ArrayLike, Filter, ParamInfo, _check, _param_info, _ptr, _record_dtype, _vec3, align_rig_heading
from ._native import lib

_KINDS = {"hinge": n.JOINT_HINGE, "2dof": n.JOINT_TWO_DOF}

#: OrientSample as a NumPy record: run_rig builds every row's samples in one array.
SAMPLE_DTYPE = _record_dtype(n.OrientSample)


@dataclass
class Joint:
    """One joint: ``kind`` ``"hinge"`` (one axis, ``axis_parent`` in the parent's frame
    and ``axis_child`` in the child's) or ``"2dof"`` (the first axis fixed in the parent,
    the second in the child); ``parent`` and ``child`` index the rig's filters. ``axes``:
    ``"sensor"`` (default), the axes are in the sensors' frames; ``"segment"``, in the
    segments' (anatomical) frames, turned into the sensors' through the mountings."""

    kind: str
    parent: int
    child: int
    axis_parent: Sequence[float]
    axis_child: Sequence[float]
    axes: str = "sensor"

    def _native(self) -> n.OrientJoint:
        if self.kind not in _KINDS:
            raise ValueError(f"joint kind must be 'hinge' or '2dof', got {self.kind!r}")
        if self.axes not in ("sensor", "segment"):
            raise ValueError(f"joint axes must be 'sensor' or 'segment', got {self.axes!r}")
        return n.OrientJoint(
            _KINDS[self.kind],
            int(self.parent),
            int(self.child),
            n.JOINT_AXES_SEGMENT if self.axes == "segment" else n.JOINT_AXES_SENSOR,
            _vec3(self.axis_parent, "axis_parent"),
            _vec3(self.axis_child, "axis_child"),
        )


class Joints:
    """A rig's joints over ``segments`` segments (segment i is the rig's filter i).
    ``mountings`` ((segments, 4) w, x, y, z, sensor to segment; None for the identity)
    give the angles' zero (the reference pose, every segment's frame the same) and the
    segments' outputs; the filters' own mountings are not read: pass each filter's
    ``mounting``. ``params``:
    joint parameters by name (``joint_params()``), set before the first update. Raises
    OrientError (``Status.INVALID_JOINT`` names the joint) for a rig that is not a forest
    or an axis that is zero or not finite, ``Status.UNKNOWN_PARAM`` or
    ``Status.PARAM_OUT_OF_RANGE`` for a parameter."""

    def __init__(self, joints: Sequence[Union[Joint, Tuple[Any, ...]]], segments: int,
                 mountings: Optional[ArrayLike] = None, params: Optional[Mapping[str, float]] = None) -> None:
        self._h: Optional[int] = None
        js = [j if isinstance(j, Joint) else Joint(*j) for j in joints]
        arr = (n.OrientJoint * max(1, len(js)))(*[j._native() for j in js])
        m = None
        if mountings is not None:
            a = np.ascontiguousarray(mountings, dtype=np.float64)
            if a.shape != (segments, 4):
                raise ValueError(f"mountings must have shape ({segments}, 4), got {a.shape}")
            m = _ptr(a, n.OrientQuaternion)
        h = c_void_p()
        _check(lib.orient_joints_new(arr, len(js), int(segments), m, byref(h)))
        self._h = h.value
        self.segments = int(segments)
        self.joints = js
        try:
            for name, value in (params or {}).items():
                self.set_param(name, value)
        except BaseException:
            self.close()
            raise

    def get_param(self, name: str) -> float:
        """The joint parameter called ``name`` (``joint_params()``), shared by every joint."""
        v = c_double()
        _check(lib.orient_joints_get_param(self._handle(), name.encode(), byref(v)))
        return v.value

    def set_param(self, name: str, value: float) -> None:
        """Sets the joint parameter called ``name`` for every joint: taken from the next
        update on (an initial standard deviation, ``*_std0``, at the next ``reset()``, or at
        once before the first update). ``Status.UNKNOWN_PARAM`` or
        ``Status.PARAM_OUT_OF_RANGE`` change nothing."""
        _check(lib.orient_joints_set_param(self._handle(), name.encode(), float(value)))

    def close(self) -> None:
        if self._h is not None:
            lib.orient_joints_free(self._h)
            self._h = None

    def __del__(self) -> None:
        self.close()

    def __enter__(self) -> "Joints":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()

    def _handle(self) -> int:
        if self._h is None:
            raise ValueError("the joints were closed")
        return self._h

    def update(self, filters: Sequence[Filter], samples: Any) -> None:
        """One row, after ``filters[s]`` took ``samples[s]``: every joint updated. ``samples``
        is an array of ``SAMPLE_DTYPE`` (one per filter) or a ctypes array of OrientSample."""
        handles = (c_void_p * len(filters))(*[f._h for f in filters])
        if isinstance(samples, np.ndarray):
            if samples.dtype != SAMPLE_DTYPE or not samples.flags.c_contiguous or samples.shape != (len(filters),):
                raise ValueError(f"samples must be a C-contiguous ({len(filters)},) array of SAMPLE_DTYPE")
            ptr = _ptr(samples, n.OrientSample)
        elif isinstance(samples, ctypes.Array) and samples._type_ is n.OrientSample and len(samples) == len(filters):
            ptr = samples
        else:
            raise ValueError(f"samples must be {len(filters)} OrientSample (a SAMPLE_DTYPE array or a ctypes array)")
        _check(lib.orient_joints_update(self._handle(), handles, ptr, len(filters)))

    def segment(self, s: int) -> np.ndarray:
        """Segment ``s``'s orientation (w, x, y, z), segment to earth: the bone rotation
        (the joints' correction and the joints' mounting ``s`` applied)."""
        q = n.OrientQuaternion()
        _check(lib.orient_joints_segment_quaternion(self._handle(), s, byref(q)))
        return np.array([q.w, q.x, q.y, q.z])

    def angles(self, k: int) -> np.ndarray:
        """Joint ``k``'s angles (rad): a hinge's ``[theta, nan]``, a 2-DoF joint's two turns
        about its first and then its second axis; zero in the reference pose."""
        a = (c_double * 2)()
        _check(lib.orient_joints_angles(self._handle(), k, a))
        return np.array(a[:])

    def rating(self, k: int) -> float:
        """Joint ``k``'s observability rating in [0, 1] (0 at rest or with a vertical hinge)."""
        r = c_double()
        _check(lib.orient_joints_rating(self._handle(), k, byref(r)))
        return r.value

    def relative_heading(self, k: int) -> Tuple[float, float]:
        """Joint ``k``'s correction of the child's heading relative to its parent (rad) and
        its standard deviation."""
        h, s = c_double(), c_double()
        _check(lib.orient_joints_relative_heading(self._handle(), k, byref(h), byref(s)))
        return h.value, s.value

    def axes(self, k: int) -> Tuple[np.ndarray, np.ndarray]:
        """Joint ``k``'s axes as refined from motion (unit, parent's and child's frame)."""
        a, b = n.OrientVec3(), n.OrientVec3()
        _check(lib.orient_joints_axes(self._handle(), k, byref(a), byref(b)))
        return np.array([a.x, a.y, a.z]), np.array([b.x, b.y, b.z])

    def reset(self) -> None:
        """Starts every joint over (after the filters' headings were aligned again)."""
        _check(lib.orient_joints_reset(self._handle()))

    def save(self) -> bytes:
        """The joints' estimates with the rig's description as a versioned, checksummed
        blob; save each filter too, and both continue bit for bit."""
        size = c_size_t()
        _check(lib.orient_joints_state_size(self._handle(), byref(size)))
        buf = (c_uint8 * size.value)()
        written = c_size_t()
        _check(lib.orient_joints_save(self._handle(), buf, size.value, byref(written)))
        return bytes(buf[: written.value])

    def load(self, blob: bytes) -> None:
        """Restores :meth:`save`'s blob into joints of the same rig; OrientError
        (INVALID_STATE) for another rig's, a filter's or a damaged blob, changing nothing."""
        data = bytes(blob)
        buf = (c_uint8 * max(len(data), 1)).from_buffer_copy(data or b"\0")
        _check(lib.orient_joints_load(self._handle(), buf, len(data)))


def joint_params() -> List[ParamInfo]:
    """The joint parameters (the tuning every joint of a rig shares), read from the
    library's table: names for ``Joints.set_param``, units, meanings, defaults, ranges."""
    count = c_uint32()
    _check(lib.orient_joint_param_count(byref(count)))
    out = []
    for i in range(count.value):
        info = n.OrientParamInfo()
        _check(lib.orient_joint_param_info(i, byref(info)))
        out.append(_param_info(info))
    return out


@dataclass
class JointAxes:
    """What :func:`estimate_hinge_axes` or :func:`estimate_two_dof_axes` found;
    ``quality`` below 0.1 can be trusted."""

    axis_parent: np.ndarray
    axis_child: np.ndarray
    quality: float


def estimate_hinge_axes(gyr_parent: ArrayLike, gyr_child: ArrayLike, guess_parent: ArrayLike,
                        guess_child: ArrayLike) -> JointAxes:
    """A hinge's axes from (N, 3) gyroscope readings (rad/s) of its two sensors at the same
    instants, started from the guesses (sensor frames)."""
    p = np.ascontiguousarray(gyr_parent, dtype=np.float64)
    c = np.ascontiguousarray(gyr_child, dtype=np.float64)
    if p.ndim != 2 or p.shape[1] != 3 or p.shape != c.shape:
        raise ValueError(f"readings must both have shape (N, 3), got {p.shape} and {c.shape}")
    out = n.OrientJointAxes()
    _check(lib.orient_estimate_hinge_axes(_ptr(p, n.OrientVec3), _ptr(c, n.OrientVec3), len(p),
                                          _vec3(guess_parent, "guess_parent"), _vec3(guess_child, "guess_child"),
                                          byref(out)))
    a, b = out.axis_parent, out.axis_child
    return JointAxes(np.array([a.x, a.y, a.z]), np.array([b.x, b.y, b.z]), out.quality)


def estimate_two_dof_axes(q_parent: ArrayLike, q_child: ArrayLike, guess_parent: ArrayLike,
                          guess_child: ArrayLike) -> JointAxes:
    """A 2-DoF joint's axes from (N, 4) orientations (w, x, y, z; sensor to earth, 6D
    estimates will do) of its two sensors at the same instants, started from the guesses:
    the first axis in the parent's sensor frame, the second in the child's."""
    p = np.ascontiguousarray(q_parent, dtype=np.float64)
    c = np.ascontiguousarray(q_child, dtype=np.float64)
    if p.ndim != 2 or p.shape[1] != 4 or p.shape != c.shape:
        raise ValueError(f"orientations must both have shape (N, 4), got {p.shape} and {c.shape}")
    out = n.OrientJointAxes()
    _check(lib.orient_estimate_two_dof_axes(_ptr(p, n.OrientQuaternion), _ptr(c, n.OrientQuaternion), len(p),
                                            _vec3(guess_parent, "guess_parent"),
                                            _vec3(guess_child, "guess_child"), byref(out)))
    a, b = out.axis_parent, out.axis_child
    return JointAxes(np.array([a.x, a.y, a.z]), np.array([b.x, b.y, b.z]), out.quality)


def _mean_heading(quats: Any, S: int) -> np.ndarray:
    """(S, 4): the rotation about the vertical by the circular mean of the S
    orientations' headings (each one's twist about the vertical)."""
    yaw = np.array([2.0 * math.atan2(quats[s].z, quats[s].w) for s in range(S)])
    mean = math.atan2(np.sin(yaw).sum(), np.cos(yaw).sum())
    return np.tile([math.cos(mean / 2), 0.0, 0.0, math.sin(mean / 2)], (S, 1))


def run_rig(filters: Sequence[Filter], joints: Optional[Joints], gyr: ArrayLike, acc: ArrayLike,
            mag: Optional[ArrayLike] = None, *, dt: ArrayLike, start: Optional[int] = None,
            align_at: Optional[int] = None, references: Optional[ArrayLike] = None) -> Dict[str, np.ndarray]:
    """A whole rig recording in one call: ``gyr``, ``acc`` (and ``mag``) of shape
    (S, N, 3), sensor s's N readings for the rig's S ``filters``; ``dt`` one value or (N,).
    Every row updates every filter (``orient_filters_update``), then from row ``start`` on
    the joints (None: no joints).

    ``align_at``: the first row after the reference pose. Before that row the filters'
    headings are aligned (``align_rig_heading``) to ``references`` ((S, 4) w, x, y, z,
    each segment's orientation in the pose), by default every segment to the segments'
    mean heading at the pose's last row (every segment's frame the same in the pose, the
    rig's common heading kept), and ``start`` defaults to it: the joints start from
    aligned headings. Without it the joints start at row ``start`` (default 0) from the
    headings as they are: align before the call, or give the joints
    ``params={"heading_std0": math.pi}`` so that they find the relative headings from the
    motion (about a minute). A segment's orientation is its filter's with the filter's
    mounting (``Filter.mounting``) for the alignment, and with the joints' ``mountings``
    for the joints' outputs: give both the same mountings.

    Returns ``segments`` (S, N, 4): each segment's orientation after each row (the joints'
    from ``start`` on, else each filter's own), and with joints ``angles`` (J, N, 2,
    radians; NaN before ``start``) and ``rating`` (J, N). A refused sample raises
    OrientError naming its row, a refused alignment (``align_rig_heading``'s statuses: a
    filter without an orientation, one listed twice) OrientError too; an ``align_at``
    outside 1..N, a ``start`` before it, ``references`` without it or not (S, 4) finite
    quaternions of a usable norm raise ValueError before any row."""
    g = np.ascontiguousarray(gyr, dtype=np.float64)
    a = np.ascontiguousarray(acc, dtype=np.float64)
    S = len(filters)
    if g.ndim != 3 or g.shape[0] != S or g.shape[2] != 3 or a.shape != g.shape:
        raise ValueError(f"gyr and acc must have shape ({S}, N, 3), got {g.shape} and {a.shape}")
    N = g.shape[1]
    m = None if mag is None else np.ascontiguousarray(mag, dtype=np.float64)
    if m is not None and m.shape != g.shape:
        raise ValueError(f"mag must have shape {g.shape}, got {m.shape}")
    d = np.broadcast_to(np.asarray(dt, dtype=np.float64), (N,))
    if joints is not None and joints.segments != S:
        raise ValueError(f"the joints have {joints.segments} segments, the rig {S} filters")
    if align_at is not None:
        if isinstance(align_at, bool) or not isinstance(align_at, (int, np.integer)) or not 0 < align_at <= N:
            raise ValueError(f"align_at must be a row in 1..{N}, got {align_at!r}")
        if start is not None and start < align_at:
            # The alignment would turn the filters' headings under running joints.
            raise ValueError(f"start ({start}) before align_at ({align_at})")
        if references is not None:
            references = np.ascontiguousarray(references, dtype=np.float64)
            if references.shape != (S, 4):
                raise ValueError(f"references must have shape ({S}, 4), got {references.shape}")
            # orient_rig_align_heading's own test of a reference (check_quaternion): finite,
            # a finite squared norm, and one no smaller than the smallest normal double.
            with np.errstate(over="ignore"):
                n2 = (references * references).sum(axis=1)
            if not (np.isfinite(references).all() and np.isfinite(n2).all() and (n2 >= np.finfo(float).tiny).all()):
                raise ValueError("references must be finite quaternions of a norm that can be normalised")
    elif references is not None:
        raise ValueError("references are for align_at")
    if start is None:
        start = 0 if align_at is None else int(align_at)
    # Row-major samples: row i's S samples are contiguous, one pointer per call.
    samples = np.zeros((N, S), dtype=SAMPLE_DTYPE)
    samples["dt"] = d[:, None]
    samples["gyro"] = g.transpose(1, 0, 2)
    samples["accel"] = a.transpose(1, 0, 2)
    samples["flags"] = n.SAMPLE_GYRO | n.SAMPLE_ACCEL
    if m is not None:
        samples["mag"] = m.transpose(1, 0, 2)
        samples["flags"] |= n.SAMPLE_MAG
    handles = (c_void_p * S)(*[f._h for f in filters])
    J = 0 if joints is None else len(joints.joints)
    segments = np.empty((S, N, 4))
    angles = np.full((J, N, 2), np.nan)
    rating = np.full((J, N), np.nan)
    quats = (n.OrientQuaternion * S)()
    q = n.OrientQuaternion()
    two = (c_double * 2)()
    r = c_double()
    jh = None if joints is None else joints._handle()
    for i in range(N):
        if i == align_at:
            # quats holds every filter's orientation after the pose's last row.
            refs = references if references is not None else _mean_heading(quats, S)
            align_rig_heading(filters, refs)
        row = _ptr(samples, n.OrientSample, i)
        st = lib.orient_filters_update(handles, row, S, quats, None)
        if st != 0:
            _check(st, i)
        if jh is not None and i >= start:
            _check(lib.orient_joints_update(jh, handles, row, S), i)
            for s in range(S):
                lib.orient_joints_segment_quaternion(jh, s, byref(q))
                segments[s, i] = (q.w, q.x, q.y, q.z)
            for k in range(J):
                lib.orient_joints_angles(jh, k, two)
                angles[k, i] = two[0], two[1]
                lib.orient_joints_rating(jh, k, byref(r))
                rating[k, i] = r.value
        else:
            for s in range(S):
                segments[s, i] = (quats[s].w, quats[s].x, quats[s].y, quats[s].z)
    if align_at == N:
        # The pose ends with the recording: the filters are left aligned for the next call.
        align_rig_heading(filters, references if references is not None else _mean_heading(quats, S))
    out = {"segments": segments}
    if joints is not None:
        out["angles"] = angles
        out["rating"] = rating
    return out


__all__ = ["Joint", "Joints", "JointAxes", "estimate_hinge_axes", "estimate_two_dof_axes", "run_rig", "SAMPLE_DTYPE"]
