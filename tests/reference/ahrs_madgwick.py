#!/usr/bin/env python3
"""Reference outputs of an independent Madgwick implementation (the Python `ahrs`
package, which follows the 2010 paper's equations with 2b) on a recorded sequence.

Writes ahrs_madgwick_marg.csv and ahrs_madgwick_imu.csv beside this script. The Rust
test tests/reference.rs replays the same rows through orient (frame NWU, the paper's
native frame, initial quaternion given) and requires agreement within 1e-9 rad per
sample.

Reproduce (any machine with pip):
    pip install ahrs==0.4.0 numpy
    python3 tests/reference/ahrs_madgwick.py

Choices, so that both sides start and step identically:
  - input: the first ROWS rows of examples/data/broad_01_excerpt.csv (BROAD trial 01,
    CC BY 4.0, see examples/data/README.md); dt per sample from consecutive t, the
    first sample using the second row's dt, as orient's replay does;
  - initial quaternion: built here from the first accelerometer and magnetometer
    sample in NWU (up = a/|a|, west = up x m normalised, north = west x up; rows of
    R_ES are [north; west; up]), then turned 3 degrees about the sensor's (1, 1, 1)
    axis, and written into the output's header line. The offset matters: at an estimate
    that fits the measurements exactly, the gradient of (21) is rounding noise and (30)
    steps beta*dt in that noise's direction, so two correct implementations would
    diverge by ~1e-4 rad on the first sample for reasons that say nothing about them;
  - every sample is an update (ahrs's batch mode would skip the first one);
  - beta 0.033 (MARG) and 0.041 (IMU), the paper's values. ahrs's own defaults
    swap them (gain_imu=0.033, gain_marg=0.041), so the gain is passed explicitly.
  - ahrs returns q unchanged when the gyroscope reads exactly zero; the chosen rows
    have no such sample (the script checks).
"""
import csv
import os
import sys

import numpy as np
from ahrs.filters import Madgwick

ROWS = 6000
HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "..", "examples", "data", "broad_01_excerpt.csv")


def quat_from_matrix(m):
    """Shepperd's method; scalar first, w >= 0."""
    tr = m[0, 0] + m[1, 1] + m[2, 2]
    cands = [tr, m[0, 0], m[1, 1], m[2, 2]]
    i = int(np.argmax(cands))
    if i == 0:
        s = 2.0 * np.sqrt(1.0 + tr)
        q = [0.25 * s, (m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, (m[1, 0] - m[0, 1]) / s]
    elif i == 1:
        s = 2.0 * np.sqrt(1.0 + m[0, 0] - m[1, 1] - m[2, 2])
        q = [(m[2, 1] - m[1, 2]) / s, 0.25 * s, (m[0, 1] + m[1, 0]) / s, (m[0, 2] + m[2, 0]) / s]
    elif i == 2:
        s = 2.0 * np.sqrt(1.0 + m[1, 1] - m[0, 0] - m[2, 2])
        q = [(m[0, 2] - m[2, 0]) / s, (m[0, 1] + m[1, 0]) / s, 0.25 * s, (m[1, 2] + m[2, 1]) / s]
    else:
        s = 2.0 * np.sqrt(1.0 + m[2, 2] - m[0, 0] - m[1, 1])
        q = [(m[1, 0] - m[0, 1]) / s, (m[0, 2] + m[2, 0]) / s, (m[1, 2] + m[2, 1]) / s, 0.25 * s]
    q = np.array(q) / np.linalg.norm(q)
    return q if q[0] >= 0 else -q


def quat_mul(a, b):
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return np.array([w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
                     w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
                     w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
                     w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2])


def initial_nwu(acc, mag):
    up = acc / np.linalg.norm(acc)
    west = np.cross(up, mag)
    west /= np.linalg.norm(west)
    north = np.cross(west, up)
    return quat_from_matrix(np.array([north, west, up]))


def main():
    with open(DATA) as fh:
        rows = list(csv.DictReader(fh))[:ROWS]
    t = np.array([float(r["t"]) for r in rows])
    gyr = np.array([[float(r[k]) for k in ("gyr_x", "gyr_y", "gyr_z")] for r in rows])
    acc = np.array([[float(r[k]) for k in ("acc_x", "acc_y", "acc_z")] for r in rows])
    mag = np.array([[float(r[k]) for k in ("mag_x", "mag_y", "mag_z")] for r in rows])
    if np.any(np.all(gyr == 0.0, axis=1)):
        sys.exit("a sample has an exactly zero gyroscope reading: ahrs would skip it")
    dt = np.diff(t, prepend=t[0] - (t[1] - t[0]))
    half = np.radians(3.0) / 2.0
    turn = np.concatenate(([np.cos(half)], np.sin(half) * np.ones(3) / np.sqrt(3.0)))
    q0 = quat_mul(initial_nwu(acc[0], mag[0]), turn)
    for name, gain, use_mag in (("marg", 0.033, True), ("imu", 0.041, False)):
        f = Madgwick(gain=gain)
        q = q0.copy()
        out = []
        for i in range(len(rows)):
            if use_mag:
                q = f.updateMARG(q, gyr=gyr[i], acc=acc[i], mag=mag[i], dt=dt[i])
            else:
                q = f.updateIMU(q, gyr=gyr[i], acc=acc[i], dt=dt[i])
            out.append(q)
        path = os.path.join(HERE, f"ahrs_madgwick_{name}.csv")
        with open(path, "w") as fh:
            fh.write(f"# ahrs 0.4.0 Madgwick {name}, beta {gain}, frame NWU, rows {ROWS} of "
                     f"examples/data/broad_01_excerpt.csv; made by tests/reference/ahrs_madgwick.py\n")
            fh.write("# q0 " + " ".join(repr(float(v)) for v in q0) + "\n")
            fh.write("qw,qx,qy,qz\n")
            for q in out:
                fh.write(",".join(repr(float(v)) for v in q) + "\n")
        print(f"wrote {path}")


if __name__ == "__main__":
    main()
