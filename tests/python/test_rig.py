"""Issue 20 from Python: mounting, heading, declination and rig calibration."""

import math

import numpy as np
import orient
import pytest
from orient import OrientError, Status


def angle(a, b):
    return 2 * math.acos(min(1.0, abs(float(np.dot(a, b)))))


def warmed(k):
    f = orient.Mahony()
    for _ in range(50):
        f.update([0.1 * k, 0.2, 0.0], [0.3 * k, 0.5, 9.7], [20.0, 3.0 * k, -40.0], dt=0.01)
    return f


def test_mounting_heading_declination():
    f = warmed(0)
    sensor = f.sensor_quaternion
    assert np.array_equal(sensor, f.quaternion)
    f.mounting = [0.8, 0.2, 0.5, -0.1]
    assert angle(f.sensor_quaternion, sensor) < 1e-6
    assert angle(f.quaternion, sensor) > 0.1
    assert abs(np.linalg.norm(f.mounting) - 1) < 1e-12
    f.set_heading(1.25)
    assert abs(f.euler[0] - 1.25) < 1e-12
    assert f.heading_offset != 0
    f.reset_heading()
    assert abs(f.euler[0]) < 1e-12
    f.declination = 0.1
    assert f.declination == 0.1
    with pytest.raises(OrientError) as e:
        f.declination = 4.0
    assert e.value.status == Status.TOO_LARGE
    with pytest.raises(OrientError) as e:
        orient.Ekf().set_heading(1.0)
    assert e.value.status == Status.NOT_INITIALIZED


def test_rig_calibration():
    fs = [warmed(k) for k in range(3)]
    refs = np.array([[1, 0, 0, 0], [math.cos(0.3), 0, math.sin(0.3), 0], [0, 0, 0, 1]], dtype=float)
    orient.calibrate_rig(fs, refs, heading=0.4)
    for f, r in zip(fs, refs):
        assert angle(f.quaternion, r) < 1e-6
    orient.calibrate_rig(fs, refs)
    fs[1].set_heading(-2.0)
    assert angle(fs[1].quaternion, refs[1]) > 0.1
    orient.align_rig_heading(fs, refs)
    assert angle(fs[1].quaternion, refs[1]) < 1e-6
    with pytest.raises(ValueError):
        orient.calibrate_rig(fs, refs[:2])
    with pytest.raises(OrientError) as e:
        orient.calibrate_rig([fs[0], orient.Ekf()], refs[:2])
    assert e.value.status == Status.NOT_INITIALIZED
