"""Issue 42 from Python: a rig's joints, a whole rig recording in one call."""

import math

import numpy as np
import orient
import pytest
from orient import OrientError, Status


def qmul(a, b):
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return np.array([w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
                     w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2])


def conj(q):
    return np.array([q[0], -q[1], -q[2], -q[3]])


def axis(x, y, z, angle):
    v = np.array([x, y, z], dtype=float)
    v /= np.linalg.norm(v)
    return np.concatenate([[math.cos(angle / 2)], v * math.sin(angle / 2)])


def hand_at(t):
    return qmul(qmul(axis(0, 0, 1, 0.5 * math.sin(0.3 * t)), axis(0, 1, 0, 0.6 * math.sin(0.7 * t))),
                axis(1, 0, 0, 0.4 * math.sin(1.1 * t)))


def flexion_at(t):
    return 0.5 + 0.8 * math.sin(1.9 * t)


def finger_at(t):
    return qmul(hand_at(t), axis(1, 0, 0, flexion_at(t)))


def readings(at, n, dt):
    """Body rates and gravity of a sensor at the joint centre, rows 1..n."""
    gyr, acc = np.empty((n, 3)), np.empty((n, 3))
    for i in range(n):
        a, b = at(i * dt), at((i + 1) * dt)
        d = qmul(conj(a), b)
        d = -d if d[0] < 0 else d
        s = np.linalg.norm(d[1:])
        gyr[i] = d[1:] * (2 * math.atan2(s, d[0]) / s / dt) if s > 1e-15 else 0.0
        acc[i] = qmul(qmul(conj(b), [0, 0, 0, 9.81]), b)[1:]
    return gyr, acc


def test_a_hinged_finger_in_one_call():
    dt, n = 0.01, 1000
    gh, ah = readings(hand_at, n, dt)
    gf, af = readings(finger_at, n, dt)
    filters = [orient.Robust(), orient.Robust()]
    x = [1.0, 0.0, 0.0]
    with orient.Joints([("hinge", 0, 1, x, x)], 2) as joints:
        out = orient.run_rig(filters, joints, np.stack([gh, gf]), np.stack([ah, af]), dt=dt)
        assert out["segments"].shape == (2, n, 4)
        assert out["angles"].shape == (1, n, 2) and out["rating"].shape == (1, n)
        # The hinge's angle is the flexion over the last seconds; its second angle NaN.
        t = (np.arange(n) + 1) * dt
        late = t > 5
        err = np.abs(out["angles"][0, late, 0] - (0.5 + 0.8 * np.sin(1.9 * t[late])))
        assert err.max() < math.radians(2.0)
        assert np.isnan(out["angles"][0, :, 1]).all()
        assert ((out["rating"] >= 0) & (out["rating"] <= 1)).all()
        np.testing.assert_allclose(joints.angles(0)[0], out["angles"][0, -1, 0])
        heading, sigma = joints.relative_heading(0)
        assert math.isfinite(heading) and sigma >= 0
        a, b = joints.axes(0)
        assert a[0] > 0.99 and b[0] > 0.99
        with pytest.raises(OrientError) as e:
            joints.rating(1)
        assert e.value.status == Status.INVALID_ARGUMENT
        blob = joints.save()
        with orient.Joints([("hinge", 0, 1, x, x)], 2) as twin:
            twin.load(blob)
            assert np.array_equal(twin.segment(1), joints.segment(1))
            with pytest.raises(OrientError) as e:
                twin.load(blob[:-1])
            assert e.value.status == Status.INVALID_STATE
        joints.reset()
        assert joints.relative_heading(0)[0] == 0.0
    # Without joints: each filter's own orientation.
    alone = orient.run_rig([orient.Robust(), orient.Robust()], None, np.stack([gh, gf]), np.stack([ah, af]), dt=dt)
    assert set(alone) == {"segments"}
    # The hinge axes from the same motion, started 5 degrees off.
    h = orient.estimate_hinge_axes(gh[:500], gf[:500], [1, 0.08, 0], [1, 0, -0.08])
    assert h.axis_parent[0] > 0.9999 and h.axis_child[0] > 0.9999 and h.quality < 0.01
    # A 2-DoF joint (the hand's z, then the finger's y) from orientations, the finger's
    # 40 degrees off in heading.
    t = np.arange(1000) * 0.01
    qp = np.array([hand_at(x) for x in t])
    qc = np.array([qmul(axis(0, 0, 1, 0.7), qmul(hand_at(x), qmul(axis(0, 0, 1, 0.25 * math.sin(2.1 * x)),
                                                                   axis(0, 1, 0, flexion_at(x))))) for x in t])
    two = orient.estimate_two_dof_axes(qp, qc, [0, 0.08, 1], [0.08, 1, 0])
    assert two.axis_parent[2] > 0.9999 and two.axis_child[1] > 0.9999 and two.quality < 0.05
    with pytest.raises(ValueError):
        orient.estimate_two_dof_axes(qp, qc[:-1], [0, 0, 1], [0, 1, 0])
    qc[5, 0] = np.nan
    with pytest.raises(OrientError) as e:
        orient.estimate_two_dof_axes(qp, qc, [0, 0, 1], [0, 1, 0])
    assert e.value.status == Status.NON_FINITE


def test_a_rig_aligned_at_the_end_of_its_pose_in_the_same_call():
    """align_at does what the two calls around align_rig_heading do, bit for bit: the
    filters alone up to the pose's last row, their headings turned to the segments' mean
    heading, then filters and joints."""
    dt, n, k = 0.01, 1000, 300
    gh, ah = readings(hand_at, n, dt)
    gf, af = readings(finger_at, n, dt)
    gyr, acc = np.stack([gh, gf]), np.stack([ah, af])
    x = [1.0, 0.0, 0.0]
    with orient.Joints([("hinge", 0, 1, x, x)], 2) as j1, orient.Joints([("hinge", 0, 1, x, x)], 2) as j2:
        one = orient.run_rig([orient.Robust(for_joints=True) for _ in range(2)], j1, gyr, acc, dt=dt, align_at=k)
        filters = [orient.Robust(for_joints=True) for _ in range(2)]
        alone = orient.run_rig(filters, None, gyr[:, :k], acc[:, :k], dt=dt)["segments"]
        pose = alone[:, -1]
        yaw = [2 * math.atan2(q[3], q[0]) for q in pose]
        mean = math.atan2(sum(map(math.sin, yaw)), sum(map(math.cos, yaw)))
        gap = (yaw[0] - yaw[1] + math.pi) % (2 * math.pi) - math.pi
        assert abs(gap) > 1e-3  # the alignment has something to do
        orient.align_rig_heading(filters, [[math.cos(mean / 2), 0.0, 0.0, math.sin(mean / 2)]] * 2)
        rest = orient.run_rig(filters, j2, gyr[:, k:], acc[:, k:], dt=dt)
        assert np.array_equal(one["segments"][:, k:], rest["segments"])
        assert np.array_equal(one["angles"][:, k:], rest["angles"], equal_nan=True)
        assert np.array_equal(one["rating"][:, k:], rest["rating"])
        assert np.isnan(one["angles"][:, :k]).all() and np.isnan(one["rating"][:, :k]).all()
        assert np.array_equal(one["segments"][:, :k], alone)
    # Given references, and a pose that ends with the recording.
    refs = [[1.0, 0.0, 0.0, 0.0]] * 2
    f1 = [orient.Robust() for _ in range(2)]
    orient.run_rig(f1, None, gyr[:, :k], acc[:, :k], dt=dt, align_at=k, references=refs)
    f2 = [orient.Robust() for _ in range(2)]
    orient.run_rig(f2, None, gyr[:, :k], acc[:, :k], dt=dt)
    unaligned = [f.quaternion for f in f2]
    orient.align_rig_heading(f2, refs)
    assert all(np.array_equal(a.quaternion, b.quaternion) for a, b in zip(f1, f2))
    assert any(not np.allclose(a.quaternion, q) for a, q in zip(f1, unaligned))
    for bad in [0, k + 1, True, 1.5]:
        with pytest.raises(ValueError):
            orient.run_rig([orient.Robust(), orient.Robust()], None, gyr[:, :k], acc[:, :k], dt=dt, align_at=bad)
    with pytest.raises(ValueError):
        orient.run_rig([orient.Robust(), orient.Robust()], None, gyr, acc, dt=dt, align_at=k, references=[[1, 0, 0, 0]])
    with pytest.raises(ValueError):
        orient.run_rig([orient.Robust(), orient.Robust()], None, gyr, acc, dt=dt, references=refs)
    # Refused before any row: a start before the alignment, a reference no rotation has.
    f3 = [orient.Robust(), orient.Robust()]
    with pytest.raises(ValueError):
        orient.run_rig(f3, None, gyr, acc, dt=dt, align_at=k, start=k - 1)
    for ref in ([0.0, 0.0, 0.0, 0.0], [np.nan, 0.0, 0.0, 1.0]):
        with pytest.raises(ValueError):
            orient.run_rig(f3, None, gyr, acc, dt=dt, align_at=k, references=[[1.0, 0, 0, 0], ref])
    assert all(np.array_equal(f.quaternion, [1.0, 0.0, 0.0, 0.0]) for f in f3)
    # The same test as the library's: a tiny norm it can normalise is a reference.
    orient.run_rig(f3, None, gyr[:, :k], acc[:, :k], dt=dt, align_at=k, references=[[1e-152, 0.0, 0.0, 0.0]] * 2)


def test_bad_rigs_and_rows_are_refused():
    x = [1.0, 0.0, 0.0]
    for joints, status, detail in [
        ([("hinge", 0, 1, x, x), ("hinge", 1, 0, x, x)], Status.INVALID_JOINT, "joint 1"),
        ([("hinge", 0, 2, x, x)], Status.INVALID_JOINT, "joint 0"),
        ([("2dof", 0, 1, [0, 0, 0], x)], Status.INVALID_JOINT, "joint 0"),
    ]:
        with pytest.raises(OrientError) as e:
            orient.Joints(joints, 2)
        assert e.value.status == status and detail in str(e.value)
    with pytest.raises(ValueError):
        orient.Joints([("ball", 0, 1, x, x)], 2)
    with pytest.raises(ValueError):
        orient.Joints([("hinge", 0, 1, x, x)], 2, mountings=np.eye(4)[:1])
    filters = [orient.Robust(), orient.Robust()]
    gyr = np.zeros((2, 10, 3))
    acc = np.tile([0.0, 0.0, 9.81], (2, 10, 1))
    gyr[1, 4, 2] = np.nan
    with orient.Joints([("hinge", 0, 1, x, x)], 2) as joints:
        with pytest.raises(OrientError) as e:
            orient.run_rig(filters, joints, gyr, acc, dt=0.01)
        assert e.value.status == Status.NON_FINITE and e.value.index == 4
        # One sample per filter, no fewer.
        with pytest.raises(ValueError):
            joints.update(filters, np.zeros(1, dtype=orient.SAMPLE_DTYPE))


def test_axes_in_the_segment_frames_go_through_the_mountings():
    x = [1.0, 0.0, 0.0]
    quarter = [math.cos(math.pi / 4), 0.0, 0.0, math.sin(math.pi / 4)]  # about z
    mountings = np.array([[1.0, 0.0, 0.0, 0.0], quarter])
    with orient.Joints([orient.Joint("hinge", 0, 1, x, x, axes="segment")], 2, mountings=mountings) as j:
        a, b = j.axes(0)
        np.testing.assert_allclose(a, x, atol=1e-12)
        np.testing.assert_allclose(b, [0.0, -1.0, 0.0], atol=1e-12)
    with pytest.raises(ValueError):
        orient.Joints([orient.Joint("hinge", 0, 1, x, x, axes="world")], 2)


def test_a_filter_for_joints_takes_the_sensor_settings():
    plain, under = orient.Robust(), orient.Robust(for_joints=True)
    assert under["bias_walk"] == pytest.approx(math.radians(0.05), abs=1e-15)
    assert under["bias_limit"] == pytest.approx(math.radians(4.0), abs=1e-15)
    assert under["rest_gyro"] == pytest.approx(math.radians(4.0), abs=1e-15)
    assert plain["bias_walk"] < under["bias_walk"]
    # Given settings come after, and other kinds have none of them.
    assert orient.Robust(for_joints=True, bias_walk=0.0)["bias_walk"] == 0.0
    m = orient.Madgwick(for_joints=True)
    assert m["beta_imu"] == orient.Madgwick()["beta_imu"]


def test_the_joint_parameters_are_listed_read_and_set_by_name():
    table = orient.joint_params()
    assert len(table) == 22 and len({p.name for p in table}) == 22
    x = [1.0, 0.0, 0.0]
    with orient.Joints([("hinge", 0, 1, x, x)], 2, params={"heading_std0": 0.3}) as joints:
        for p in table:
            want = 0.3 if p.name == "heading_std0" else p.default
            assert joints.get_param(p.name) == want and p.min <= p.default <= p.max
        # Before the first update an initial standard deviation applies at once.
        assert joints.relative_heading(0) == (0.0, pytest.approx(0.3, abs=1e-15))
        joints.set_param("gate", 2.5)
        assert joints.get_param("gate") == 2.5
        for name, value, status in [("gate", -1.0, Status.PARAM_OUT_OF_RANGE),
                                    ("gate", float("nan"), Status.PARAM_OUT_OF_RANGE),
                                    ("beta", 1.0, Status.UNKNOWN_PARAM)]:
            with pytest.raises(OrientError) as e:
                joints.set_param(name, value)
            assert e.value.status == status
        assert joints.get_param("gate") == 2.5
    with pytest.raises(OrientError) as e:
        orient.Joints([("hinge", 0, 1, x, x)], 2, params={"max_rate": 0.0})
    assert e.value.status == Status.PARAM_OUT_OF_RANGE
