"""Error over time against ground truth, as the replay tool's ``--svg`` draws it, with
matplotlib (optional: ``pip install matplotlib``; imported only when a plot is made)."""

from __future__ import annotations

from typing import Any, Mapping, Optional

import numpy as np

from ._filter import BatchResult
from .eval import Recording, bands, error_angles

ANGLES = ("total", "heading", "inclination")
BAND_COLORS = {"rest": "#2ca02c", "mag unused": "#d62728", "accel unused": "#ff7f0e", "gap": "#7f7f7f"}


def plot_errors(rec: Recording, results: Mapping[str, BatchResult], path: Optional[str] = None) -> Any:
    """Draws the total, heading and inclination error (degrees) over time of each filter
    in ``results`` (label -> :class:`BatchResult`, quaternions in ENU) against
    ``rec.truth``, one panel per angle, with shaded bands where each filter reported
    rest, an unused magnetometer or accelerometer, or a gap (:func:`orient.eval.bands`).
    Saves to ``path`` when given (format from its suffix, e.g. ``.svg``) and returns the
    matplotlib Figure.

    Raises ImportError when matplotlib is not installed, ValueError without ground truth.
    """
    try:
        import matplotlib.pyplot as plt
    except ImportError as e:  # pragma: no cover - exercised when matplotlib is absent
        raise ImportError("orient.plot needs matplotlib: pip install matplotlib") from e
    if rec.truth is None:
        raise ValueError("the recording has no ground truth (quat_* columns)")
    fig, axes = plt.subplots(len(ANGLES), 1, sharex=True, figsize=(10, 7))
    t = rec.t
    for label, result in results.items():
        err = np.degrees(error_angles(result.quaternion, rec.truth))
        for i, (ax, angle) in enumerate(zip(axes, ANGLES)):
            (line,) = ax.plot(t, err[:, i], linewidth=0.8, label=f"{label} {angle}")
            line.set_gid(f"{label}-{angle}")
        for name, spans in bands(t, result, has_mag=rec.mag is not None).items():
            for k, (t0, t1) in enumerate(spans):
                patch = axes[0].axvspan(
                    t0, t1, color=BAND_COLORS[name], alpha=0.15, label=f"{label} {name}" if k == 0 else None
                )
                patch.set_gid(f"{label}-band-{name}-{k}")
    for ax, angle in zip(axes, ANGLES):
        ax.set_ylabel(f"{angle} [deg]")
        ax.legend(loc="upper right", fontsize="small")
    axes[-1].set_xlabel("time [s]")
    fig.suptitle("orientation error against ground truth")
    fig.tight_layout()
    if path is not None:
        fig.savefig(path)
    return fig
