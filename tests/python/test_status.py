"""Every status of the C API, as the Python package reports it: an OrientError carrying
the status and the library's message, and a refused call changes nothing (the saved
state is byte-identical before and after)."""

import ctypes

import numpy as np
import orient
import pytest
from orient import OrientError, Status
from orient import _native as n

GYR, ACC, MAG = [0.01, -0.02, 0.3], [0.1, 0.2, 9.8], [0.0, 20.0, -40.0]


def warmed(kind=orient.Madgwick, **settings):
    f = kind(**settings)
    for _ in range(5):
        f.update(GYR, ACC, MAG, dt=0.01)
    return f


def refused(f, status, call):
    before = f.save()
    with pytest.raises(OrientError) as e:
        call()
    assert e.value.status == status, e.value
    assert e.value.message and e.value.message == str(e.value).split(": ", 1)[1]
    assert f.save() == before, "a refused call changed the filter"
    return e.value


@pytest.mark.parametrize(
    "status, gyr, acc, mag, dt",
    [
        (Status.NON_FINITE, [np.nan, 0, 0], ACC, MAG, 0.01),
        (Status.NON_FINITE, GYR, ACC, [0, np.inf, 0], 0.01),
        (Status.INVALID_DT, GYR, ACC, MAG, 0.0),
        (Status.INVALID_DT, GYR, ACC, MAG, -0.01),
        (Status.INVALID_DT, GYR, ACC, MAG, np.nan),
        (Status.ZERO_VECTOR, GYR, [0, 0, 0], MAG, 0.01),
        (Status.ZERO_VECTOR, GYR, ACC, [1e-170, 0, 0], 0.01),
        (Status.TOO_LARGE, GYR, [1e300, 1e300, 0], MAG, 0.01),
        (Status.SATURATED, [35.0, 0, 0], ACC, MAG, 0.01),
    ],
)
def test_refused_samples_raise_their_status_and_change_nothing(status, gyr, acc, mag, dt):
    for kind in [orient.Madgwick, orient.Robust, orient.Ekf]:
        f = warmed(kind, gyro_range=34.9)
        refused(f, status, lambda: f.update(gyr, acc, mag, dt=dt))
        # ... and in a batch, at its index, with the samples before it applied.
        twin = warmed(kind, gyro_range=34.9)
        g = np.array([GYR, GYR, gyr], dtype=float)
        a = np.array([ACC, ACC, acc], dtype=float)
        m = np.array([MAG, MAG, mag], dtype=float)
        with pytest.raises(OrientError) as e:
            f.update_batch(g, a, m, dt=np.array([0.01, 0.01, dt]))
        assert (e.value.status, e.value.index) == (status, 2)
        assert e.value.message.startswith("sample 2: ")
        twin.update_batch(g[:2], a[:2], m[:2], dt=0.01)
        assert f.save() == twin.save()


def test_not_initialized_no_data_and_dt_beyond_its_bound():
    f = orient.Madgwick()
    refused(f, Status.NOT_INITIALIZED, lambda: f.update(GYR, dt=0.01))
    g = orient.Madgwick(initial="identity")
    g.update(GYR, dt=0.01)
    refused(g, Status.NO_DATA, lambda: g.linear_accel)
    # With the gap policy off, a dt above 1e6 s is still refused, before any arithmetic.
    h = warmed(orient.Madgwick, gap_dt=0.0)
    refused(h, Status.INVALID_DT, lambda: h.update(GYR, ACC, MAG, dt=2e6))


def test_settings_unknown_out_of_range_and_bad_kind_or_frame():
    e = refused(warmed(), Status.UNKNOWN_PARAM, lambda: orient.Madgwick(nope=1.0))
    assert "nope" in e.message
    e = refused(warmed(), Status.PARAM_OUT_OF_RANGE, lambda: orient.Madgwick(beta_imu=-1.0))
    assert "beta_imu" in e.message
    f = warmed()
    refused(f, Status.PARAM_OUT_OF_RANGE, lambda: f.__setitem__("beta_imu", float("nan")))
    refused(f, Status.UNKNOWN_PARAM, lambda: f["tau_acc"])
    with pytest.raises(OrientError) as e:
        orient.Filter("kalman")
    assert e.value.status == Status.INVALID_ARGUMENT
    with pytest.raises(OrientError) as e:
        orient.Robust(frame="xyz")
    assert e.value.status == Status.INVALID_ARGUMENT
    refused(f, Status.NON_FINITE, lambda: f.set_quaternion([np.nan, 0, 0, 0]))
    refused(f, Status.ZERO_VECTOR, lambda: f.set_quaternion([0, 0, 0, 0]))
    refused(f, Status.TOO_LARGE, lambda: f.set_quaternion([1e200, 1e200, 0, 0]))


def test_state_blobs_round_trip_and_bad_blobs_are_invalid_state():
    f = warmed(orient.Robust)
    blob = f.save()
    assert isinstance(blob, bytes) and len(blob) == f.state_size
    g = orient.Robust()
    g.load(blob)
    for x in (f, g):
        x.update(GYR, ACC, MAG, dt=0.01)
    assert (f.quaternion.view(np.uint64) == g.quaternion.view(np.uint64)).all()
    corrupt = bytearray(blob)
    corrupt[len(corrupt) // 2] ^= 0x40
    refused(g, Status.INVALID_STATE, lambda: g.load(bytes(corrupt)))
    refused(g, Status.INVALID_STATE, lambda: g.load(blob[:-1]))
    refused(g, Status.INVALID_STATE, lambda: g.load(b""))
    m = warmed()
    refused(m, Status.INVALID_STATE, lambda: m.load(blob))


def test_closed_filters_and_the_native_paths_python_never_takes():
    f = warmed()
    f.close()
    with pytest.raises(OrientError) as e:
        f.update(GYR, ACC, MAG, dt=0.01)
    assert e.value.status == Status.INVALID_HANDLE
    check = orient._filter._check
    lib = n.lib
    g = warmed()
    h = g._handle
    # Reached only through the raw layer: each must still become an OrientError.
    raw = {
        Status.NULL_POINTER: lambda: lib.orient_filter_quaternion(h, None),
        Status.INVALID_HANDLE: lambda: lib.orient_filter_reset(ctypes.addressof((ctypes.c_uint64 * 16)())),
        Status.INVALID_ARGUMENT: lambda: lib.orient_filter_update_arrays(
            h, 3, (ctypes.c_double * 2)(0.01, 0.01), 2, (ctypes.c_double * 9)(), None, None, None, None, None, None),
        Status.MISSING_SENSOR: lambda: lib.orient_filter_update(
            h, ctypes.byref(n.OrientSample(dt=0.01, accel=n.OrientVec3(*ACC), flags=n.SAMPLE_ACCEL))),
        Status.COUNT_TOO_LARGE: lambda: lib.orient_filter_update_arrays(
            h, 2**63, (ctypes.c_double * 1)(0.01), 1, (ctypes.c_double * 3)(), None, None, None, None, None, None),
        Status.BUFFER_TOO_SMALL: lambda: lib.orient_filter_save(
            h, (ctypes.c_uint8 * 8)(), 8, ctypes.byref(ctypes.c_size_t())),
    }
    before = g.save()
    for status, call in raw.items():
        with pytest.raises(OrientError) as e:
            check(call())
        assert e.value.status == status, status
    assert g.save() == before
    config = n.OrientConfig()
    check(lib.orient_config_default(n.Kind.MADGWICK, ctypes.byref(config)))
    config.struct_size -= 8
    with pytest.raises(OrientError) as e:
        check(lib.orient_filter_new(ctypes.byref(config), ctypes.byref(ctypes.c_void_p())))
    assert e.value.status == Status.VERSION_MISMATCH


def test_every_status_has_a_message():
    # UNSUPPORTED_KIND (every kind is built) and PANIC (a bug) cannot be provoked.
    for s in Status:
        assert orient.status_message(s) not in ("", "unknown status code"), s
    assert orient.status_message(99) == "unknown status code"
