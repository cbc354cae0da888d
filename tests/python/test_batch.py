"""update_batch: the same bits as single updates, per-sample flags and diagnostics,
arrays read in place, dt as a scalar or an array, and the skip mode."""

import numpy as np
import orient
import pytest
from orient._filter import _rows

rng = np.random.default_rng(7)
N = 400
GYR = rng.normal(0.0, 0.3, (N, 3))
ACC = np.array([0.3, -0.2, 9.8]) + rng.normal(0.0, 0.5, (N, 3))
MAG = np.array([5.0, 20.0, -40.0]) + rng.normal(0.0, 2.0, (N, 3))
DT = 0.01 + rng.uniform(-0.002, 0.002, N)
# Still for the first 2.5 s: McGinnis' and GMVDK's start-up periods need a still sensor.
GYR[:250] = rng.normal(0.0, 0.002, (250, 3))
ACC[:250] = np.array([0.3, -0.2, 9.8]) + rng.normal(0.0, 0.01, (250, 3))

# Every kind of the enum (generated from the header), by its class: a new kind without
# a class fails here.
KINDS = [getattr(orient, k.name.capitalize()) for k in orient.Kind]


def u64(a):
    return np.ascontiguousarray(a, dtype=np.float64).view(np.uint64)


@pytest.mark.parametrize("kind", KINDS)
def test_batch_equals_single_updates_with_flags_and_diagnostics_per_sample(kind):
    single, batch = kind(), kind()
    r = batch.update_batch(GYR, ACC, MAG, dt=DT)
    assert r.quaternion.shape == (N, 4) and r.flags.shape == (N,) and r.diagnostics.shape == (N,)
    for i in range(N):
        q = single.update(GYR[i], ACC[i], MAG[i], dt=DT[i])
        assert (u64(q) == u64(r.quaternion[i])).all(), i
        assert single.flags == r.flags[i], i
        d = single.diagnostics
        for name, value in d.items():
            assert (u64(value) == u64(r.diagnostics[name][i])).all(), (i, name)
        absent = set(orient.DIAGNOSTICS_DTYPE.names) - set(d) - {"present", "reserved"}
        for name in absent:
            assert np.isnan(r.diagnostics[name][i]).all(), (i, name)
    assert r.accel_used.any()
    assert (r.status == 0).all()


def test_6d_and_gyro_only_batches_match_single_updates():
    for acc, mag in [(ACC, None), (None, None)]:
        single, batch = orient.Madgwick(initial="identity"), orient.Madgwick(initial="identity")
        r = batch.update_batch(GYR, acc, mag, dt=0.01)
        for i in range(N):
            q = single.update(GYR[i], None if acc is None else acc[i], dt=0.01)
        assert (u64(q) == u64(r.quaternion[-1])).all()
        assert not r.mag_used.any()
        assert r.accel_used.all() == (acc is not None)


def test_scalar_dt_equals_a_constant_array_and_chunks_equal_one_batch():
    a, b, c = orient.Robust(), orient.Robust(), orient.Robust()
    ra = a.update_batch(GYR, ACC, MAG, dt=0.01)
    rb = b.update_batch(GYR, ACC, MAG, dt=np.full(N, 0.01))
    assert (u64(ra.quaternion) == u64(rb.quaternion)).all()
    parts = [c.update_batch(GYR[k:k + 57], ACC[k:k + 57], MAG[k:k + 57], dt=0.01) for k in range(0, N, 57)]
    assert (u64(np.concatenate([p.quaternion for p in parts])) == u64(ra.quaternion)).all()


def test_contiguous_float64_arrays_are_read_in_place_and_others_converted():
    assert _rows(GYR, "gyr") is GYR
    strided = np.asfortranarray(GYR)
    assert _rows(strided, "gyr") is not strided
    as_f32 = GYR.astype(np.float32)
    a, b = orient.Madgwick(), orient.Madgwick()
    ra = a.update_batch(GYR[::2], ACC[::2], MAG[::2], dt=0.01)  # non-contiguous views
    rb = b.update_batch(GYR[::2].copy(), ACC[::2].copy(), MAG[::2].copy(), dt=0.01)
    assert (u64(ra.quaternion) == u64(rb.quaternion)).all()
    assert orient.Madgwick().update_batch(as_f32.tolist(), ACC, dt=0.01).quaternion.shape == (N, 4)


def test_shapes_are_checked():
    f = orient.Madgwick()
    with pytest.raises(ValueError):
        f.update_batch(GYR[:, :2], ACC, dt=0.01)
    with pytest.raises(ValueError):
        f.update_batch(GYR, ACC[:-1], dt=0.01)
    with pytest.raises(ValueError):
        f.update_batch(GYR, ACC, dt=np.full(N - 1, 0.01))
    with pytest.raises(ValueError):
        f.update([1.0, 2.0], dt=0.01)
    assert f.update_batch(np.empty((0, 3)), dt=0.01).quaternion.shape == (0, 4)


def test_skip_mode_leaves_refused_samples_out_like_the_replay_tool():
    acc = ACC.copy()
    acc[[10, 11, 200]] = np.nan
    f, ref = orient.Robust(), orient.Robust()
    r = f.update_batch(GYR, acc, MAG, dt=DT, errors="skip")
    assert list(np.flatnonzero(r.status)) == [10, 11, 200]
    assert r.status[10] == orient.Status.NON_FINITE
    for i in range(N):
        try:
            ref.update(GYR[i], acc[i], MAG[i], dt=DT[i])
        except orient.OrientError:
            pass
        assert (u64(ref.quaternion) == u64(r.quaternion[i])).all(), i
        assert ref.flags == r.flags[i]
    with pytest.raises(ValueError):
        f.update_batch(GYR, acc, MAG, dt=DT, errors="ignore")


def test_settings_by_name_come_from_the_library_table():
    table = orient.Robust.params()
    names = [p.name for p in table]
    assert names[:4] == ["gravity", "gyro_range", "accel_range", "gap_dt"] and "tau_acc" in names
    tau = next(p for p in table if p.name == "tau_acc")
    f = orient.Robust(tau_acc=tau.max)
    assert f["tau_acc"] == tau.max
    assert orient.Robust()["tau_acc"] == tau.default
    f["tau_acc"] = tau.min
    assert f["tau_acc"] == tau.min
    assert {p.name for p in orient.params("madgwick")} >= {"beta_imu", "beta_marg"}


def test_frames_initial_orientation_and_outputs():
    enu, ned = orient.Madgwick(), orient.Madgwick(frame="ned")
    for f in (enu, ned):
        f.update_batch(GYR, ACC, MAG, dt=0.01)
    # The same sensor axis seen in ENU (east, north, up) and in NED (north, east, down).
    assert not np.allclose(enu.quaternion, ned.quaternion)
    z_enu, z_ned = enu.rotation_matrix @ [0, 0, 1], ned.rotation_matrix @ [0, 0, 1]
    assert np.allclose(z_enu, z_ned[[1, 0, 2]] * [1, 1, -1], atol=1e-3)
    g = orient.Madgwick(initial=[0.0, 0.0, 0.0, 2.0])
    assert np.allclose(g.quaternion, [0.0, 0.0, 0.0, 1.0], rtol=0, atol=1e-15)  # given, normalised
    assert (orient.Madgwick().quaternion == [1.0, 0.0, 0.0, 0.0]).all()  # identity until the first sample
    assert np.allclose(np.linalg.norm(enu.gravity), 9.80665)
    assert enu.linear_accel.shape == (3,) and enu.linear_accel_earth.shape == (3,)
    yaw, pitch, roll = enu.euler
    assert -np.pi <= yaw <= np.pi
    enu.reset()
    assert (enu.quaternion == [1, 0, 0, 0]).all() and enu.flags == 0
