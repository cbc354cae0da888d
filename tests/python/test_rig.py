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
    # 6D filters, each heading its own: an offset set before changes nothing.
    fs[1].set_heading(2.0)
    orient.calibrate_rig_each(fs, refs)
    offset = fs[1].heading_offset
    for f, r in zip(fs, refs):
        assert angle(f.quaternion, r) < 1e-6
    fs[1].set_heading(-1.0)
    orient.calibrate_rig_each(fs, refs)
    assert abs(fs[1].heading_offset - offset) < 1e-12
    with pytest.raises(ValueError):
        orient.calibrate_rig(fs, refs[:2])
    with pytest.raises(OrientError) as e:
        orient.calibrate_rig([fs[0], orient.Ekf()], refs[:2])
    assert e.value.status == Status.NOT_INITIALIZED


def test_sensor_models_and_calibrators():
    offset, spread = orient.gyro_offset([[0.011, -0.02, 0.03], [0.009, -0.02, 0.03]])
    assert np.allclose(offset, [0.01, -0.02, 0.03]) and spread > 0
    f, g = orient.Mahony(), orient.Mahony()
    assert f.sensor_model("gyro") is None
    f.set_sensor_model("gyro", np.eye(3), offset)
    m, o = f.sensor_model("gyro")
    assert np.array_equal(m, np.eye(3)) and np.array_equal(o, offset)
    for _ in range(50):
        f.update([0.21, -0.02, 0.03], [0.3, 0.2, 9.7], dt=0.01)
        g.update(np.array([0.21, -0.02, 0.03]) - offset, [0.3, 0.2, 9.7], dt=0.01)
    assert np.array_equal(f.quaternion, g.quaternion)
    f.set_sensor_model("gyro", None)
    assert f.sensor_model("gyro") is None
    with pytest.raises(OrientError) as e:
        f.set_sensor_model("mag", np.zeros((3, 3)))
    assert e.value.status == Status.ZERO_VECTOR
    cal = orient.MagCalibrator()
    assert cal.solve() is None
    idx = (np.arange(288) * 97) % 288
    th, ph = np.pi * (idx // 24 + 0.5) / 12, 2 * np.pi * (idx % 24) / 24
    cal.add(np.c_[60 * np.sin(th) * np.cos(ph) + 10, 45 * np.sin(th) * np.sin(ph) - 20, 50 * np.cos(th) + 5])
    fit = cal.solve()
    assert np.allclose(fit.hard_iron, [10, -20, 5], atol=1e-6)
    assert fit.trustworthy and fit.samples == 288


def test_heading_uncertainty():
    """The robust kind's heading sigma settles while the magnetometer is used and grows
    at every sample without it; the EKF gives heading and inclination; Mahony none."""
    f = orient.Filter("robust")
    assert f.uncertainty == {}
    # 30 s: rest is seen, and the bias uncertainty settles to its value after a rest.
    for _ in range(3000):
        f.update([0.0, 0.0, 0.0], [0.0, 0.0, 9.81], [0.0, 20.0, -40.0], dt=0.01)
    # The header's settle value at rest in a clean field: sqrt(sigma_m^2 + (sigma_b tau)^2).
    settle = np.hypot(f["mag_heading_sigma"], f["bias_sigma_rest"] * f["tau_mag"])
    assert abs(f.uncertainty["heading"] - settle) < 0.05 * settle  # "about": 2.6 % below
    before = f.uncertainty["heading"]
    for _ in range(100):
        f.update([0.0, 0.0, 0.0], [0.0, 0.0, 9.81], dt=0.01)
        now = f.uncertainty["heading"]
        assert now > before
        before = now
    assert set(f.uncertainty) == {"heading"}
    assert set(warmed(1).uncertainty) == set()
    e = orient.Filter("ekf")
    e.update([0.0, 0.0, 0.0], [0.0, 0.0, 9.81], [0.0, 20.0, -40.0], dt=0.01)
    u = e.uncertainty
    assert set(u) == {"heading", "inclination"} and 0 < u["heading"] < 2 and 0 < u["inclination"] < 2
