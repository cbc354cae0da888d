"""Recordings and scoring, as the replay tool does them (tools/src/eval.rs): read the CSV of
shared/data/FORMAT.md, replay it through a filter, and score the estimates against the
optical ground truth with BROAD's rule."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Optional, Union

import numpy as np

from ._filter import BatchResult, Filter
from ._native import FLAG_ACCEL_USED, FLAG_GAP, FLAG_MAG_USED


@dataclass
class Recording:
    """One recording: ``t`` (N,) s; ``gyr``, ``acc`` (N, 3); ``mag`` (N, 3) or None;
    ``truth`` (N, 4) ENU q_ES (NaN where not tracked) or None; ``movement`` (N,) bool
    (the rows BROAD scores) or None."""

    t: np.ndarray
    gyr: np.ndarray
    acc: np.ndarray
    mag: Optional[np.ndarray]
    truth: Optional[np.ndarray]
    movement: Optional[np.ndarray]

    @property
    def dt(self) -> np.ndarray:
        """(N,) dt from consecutive ``t``; the first row takes the second row's dt."""
        if len(self.t) < 2:
            return np.full(len(self.t), 0.01)
        d = np.diff(self.t)
        return np.concatenate([d[:1], d])


def read_recording(path: Union[str, Path], with_mag: bool = True) -> Recording:
    """Reads a recording CSV: a header row naming the columns (any order, extra columns
    ignored), ``t``, ``gyr_*``, ``acc_*``, and ``mag_*`` when ``with_mag``; ``quat_*`` and
    ``movement`` when present. Raises ValueError for a missing column."""
    with open(path, encoding="utf-8") as f:
        names = [c.strip() for c in f.readline().split(",")]
        data = np.loadtxt(f, delimiter=",", dtype=np.float64, ndmin=2)

    def cols(*wanted: str, required: bool = True) -> Optional[np.ndarray]:
        missing = [w for w in wanted if w not in names]
        if missing:
            if required:
                raise ValueError(f"{path}: missing column '{missing[0]}'")
            return None
        return np.ascontiguousarray(data[:, [names.index(w) for w in wanted]])

    xyz = lambda p: (f"{p}_x", f"{p}_y", f"{p}_z")  # noqa: E731
    movement = cols("movement", required=False)
    return Recording(
        t=cols("t")[:, 0],
        gyr=cols(*xyz("gyr")),
        acc=cols(*xyz("acc")),
        mag=cols(*xyz("mag")) if with_mag else None,
        truth=cols("quat_w", "quat_x", "quat_y", "quat_z", required=False),
        movement=None if movement is None else movement[:, 0] == 1.0,
    )


def replay(filter: Filter, rec: Recording, with_mag: bool = True) -> BatchResult:
    """Runs every sample of ``rec`` through ``filter`` (refused samples left out and
    marked in ``status``, as the replay tool does)."""
    mag = rec.mag if with_mag else None
    return filter.update_batch(rec.gyr, rec.acc, mag, dt=rec.dt, errors="skip")


@dataclass(frozen=True)
class Scores:
    """RMSE in degrees over the scored samples, and how many were scored."""

    total: float
    heading: float
    inclination: float
    count: int


def _normalized(q: np.ndarray) -> np.ndarray:
    return q / np.linalg.norm(q, axis=-1, keepdims=True)


def _error(est: np.ndarray, truth: np.ndarray) -> np.ndarray:
    """e = est * conj(truth), both normalised, then normalised (Hamilton, w first)."""
    a, b = _normalized(np.asarray(est, dtype=np.float64)), _normalized(np.asarray(truth, dtype=np.float64))
    aw, ax, ay, az = a[..., 0], a[..., 1], a[..., 2], a[..., 3]
    bw, bx, by, bz = b[..., 0], -b[..., 1], -b[..., 2], -b[..., 3]
    e = np.stack(
        [
            aw * bw - ax * bx - ay * by - az * bz,
            aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw,
        ],
        axis=-1,
    )
    return _normalized(e)


def error_angles(est: np.ndarray, truth: np.ndarray) -> np.ndarray:
    """(N, 3) BROAD's error angles in radians, total, heading, inclination, between ENU
    estimates and truth (N, 4): ``e = est * conj(truth)``, total ``2 acos|e.w|``, heading
    ``2 atan2(|e.z|, |e.w|)``, inclination ``2 acos sqrt(e.w^2 + e.z^2)``."""
    e = _error(est, truth)
    w, z = np.abs(e[..., 0]), np.abs(e[..., 3])
    total = 2.0 * np.arccos(np.clip(w, 0.0, 1.0))
    heading = 2.0 * np.arctan2(z, w)
    inclination = 2.0 * np.arccos(np.clip(np.sqrt(w * w + z * z), 0.0, 1.0))
    return np.stack([total, heading, inclination], axis=-1)


def _scored(est: np.ndarray, truth: np.ndarray, movement: np.ndarray) -> np.ndarray:
    return movement & np.isfinite(truth).all(axis=1) & np.isfinite(est).all(axis=1)


def score(est: np.ndarray, truth: np.ndarray, movement: np.ndarray) -> Scores:
    """BROAD's score (FORMAT.md "Scoring"): RMSE of each angle over rows with
    ``movement``, rows whose truth is NaN left out, in degrees."""
    keep = _scored(est, truth, movement)
    count = int(keep.sum())
    if count == 0:
        return Scores(float("nan"), float("nan"), float("nan"), 0)
    angles = error_angles(est[keep], truth[keep])
    rms = np.degrees(np.sqrt(np.mean(angles * angles, axis=0)))
    return Scores(float(rms[0]), float(rms[1]), float(rms[2]), count)


def remove_heading_offset(est: np.ndarray, truth: np.ndarray, movement: np.ndarray) -> tuple:
    """For a filter without magnetometer: the estimates with one constant heading offset
    removed (the circular mean of the heading error over the scored rows), and that
    offset in radians."""
    keep = _scored(est, truth, movement)
    e = _error(est[keep], truth[keep])
    psi = 2.0 * np.arctan2(e[:, 3], e[:, 0])
    delta = float(np.arctan2(np.sin(psi).sum(), np.cos(psi).sum()))
    c, s = np.cos(-delta / 2.0), np.sin(-delta / 2.0)
    w, x, y, z = est[:, 0], est[:, 1], est[:, 2], est[:, 3]
    fixed = np.stack([c * w - s * z, c * x - s * y, c * y + s * x, c * z + s * w], axis=-1)
    return fixed, delta


def bands(t: np.ndarray, result: BatchResult, has_accel: bool = True, has_mag: bool = True) -> dict:
    """Time spans where the filter reported a condition, for plots: ``{name: [(t0, t1), ...]}``
    for ``rest`` (diagnostics.rest, kinds with a rest detector), ``mag unused`` (a
    magnetometer was given but the update did not use it: a rejected disturbance, or a
    kind that does not use it then), ``accel unused`` (likewise for the accelerometer:
    acceleration rejection) and ``gap`` (FLAG_GAP), as the replay tool's ``--svg`` draws. A condition no sample shows is absent."""
    flags = result.flags
    conditions = {
        "rest": result.rest,
        "mag unused": (flags & FLAG_MAG_USED) == 0 if has_mag else np.zeros(len(flags), bool),
        "accel unused": (flags & FLAG_ACCEL_USED) == 0 if has_accel else np.zeros(len(flags), bool),
        "gap": (flags & FLAG_GAP) != 0,
    }
    out = {}
    for name, mask in conditions.items():
        spans = _spans(t, np.asarray(mask, bool) & (result.status == 0))
        if spans:
            out[name] = spans
    return out


def _spans(t: np.ndarray, mask: np.ndarray) -> list:
    if not mask.any():
        return []
    edges = np.diff(np.concatenate([[0], mask.astype(np.int8), [0]]))
    starts, ends = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1) - 1
    return [(float(t[a]), float(t[b])) for a, b in zip(starts, ends)]
