"""ctypes declarations of the C API in include/orient.h, and the loaded library.

Only the C API's numbers and layouts are written here; parameter names, units, defaults
and ranges are read from the library at run time (orient_param_info).
tests/python/test_header.py fails when anything here drifts from orient.h.
"""

from __future__ import annotations

import ctypes
import enum
import os
import sys
from ctypes import POINTER, Structure, c_char_p, c_double, c_int32, c_size_t, c_uint8, c_uint32, c_uint64, c_void_p
from pathlib import Path

import numpy as np

ABI_VERSION = 1
MAX_PARAMS = 128

SAMPLE_GYRO = 1
SAMPLE_ACCEL = 2
SAMPLE_MAG = 4

FLAG_INITIALIZED = 1
FLAG_ACCEL_USED = 2
FLAG_MAG_USED = 4
FLAG_GAP = 8
FLAG_REACQUIRED = 16
FLAG_REACQUIRE_PENDING = 32
FLAG_ACCEL_REJECTED = 64
FLAG_MAG_REJECTED = 128
FLAG_MAG_DISTURBED = 256
FLAG_REST = 512
FLAG_SATURATED = 1024
FLAG_SAME_INSTANT = 2048

PARAM_FLAG_ZERO_OFF = 1

DIAG_GYRO_BIAS = 1
DIAG_REST = 2
DIAG_ALPHA = 4
DIAG_MU_KA = 8
DIAG_MU_KM = 16
DIAG_MU_K = 32
DIAG_RATE = 64
DIAG_COVARIANCE = 128
UNCERTAINTY_HEADING = 1
UNCERTAINTY_INCLINATION = 2


class Status(enum.IntEnum):
    """OrientStatus: the result of every fallible call (fixed numbers)."""

    OK = 0
    NULL_POINTER = 1
    INVALID_HANDLE = 2
    UNSUPPORTED_KIND = 3
    INVALID_ARGUMENT = 4
    UNKNOWN_PARAM = 5
    PARAM_OUT_OF_RANGE = 6
    NON_FINITE = 7
    INVALID_DT = 8
    ZERO_VECTOR = 9
    TOO_LARGE = 10
    SATURATED = 11
    MISSING_SENSOR = 12
    NOT_INITIALIZED = 13
    NO_DATA = 14
    NUMERIC = 15
    COUNT_TOO_LARGE = 16
    VERSION_MISMATCH = 17
    PANIC = 18
    BUFFER_TOO_SMALL = 19
    INVALID_STATE = 20
    OUT_OF_MEMORY = 21


class Kind(enum.IntEnum):
    """OrientKind."""

    MADGWICK = 1
    MAHONY = 2
    COMPLEMENTARY = 3
    EKF = 4
    GMVDK = 5
    ROBUST = 6


class Frame(enum.IntEnum):
    """OrientFrame: the earth frame every output is expressed in."""

    ENU = 0
    NED = 1
    NWU = 2


class Init(enum.IntEnum):
    """OrientInit."""

    ACC_MAG = 0
    IDENTITY = 1
    GIVEN = 2


class OrientQuaternion(Structure):
    _fields_ = [("w", c_double), ("x", c_double), ("y", c_double), ("z", c_double)]


class OrientVec3(Structure):
    _fields_ = [("x", c_double), ("y", c_double), ("z", c_double)]


class OrientSensorModel(Structure):
    _fields_ = [("matrix", c_double * 9), ("offset", OrientVec3)]


class OrientMagCalibrator(Structure):
    _fields_ = [
        ("sums", c_double * 55),
        ("scale", c_double),
        ("mean", OrientVec3),
        ("count", c_uint64),
        ("bins", c_uint64),
        ("rejected", c_uint64),
        ("streak", c_uint64),
        ("gate", c_double * 10),
    ]


class OrientMagFit(Structure):
    _fields_ = [
        ("model", OrientSensorModel),
        ("field", c_double),
        ("residual", c_double),
        ("coverage", c_double),
        ("samples", c_uint64),
        ("trustworthy", c_int32),
        ("reserved", c_int32),
    ]


SENSOR_GYRO, SENSOR_ACCEL, SENSOR_MAG = 0, 1, 2


class OrientConfig(Structure):
    _fields_ = [
        ("struct_size", c_uint32),
        ("kind", c_int32),
        ("frame", c_int32),
        ("init", c_int32),
        ("initial", OrientQuaternion),
        ("params", c_double * MAX_PARAMS),
    ]


class OrientParamInfo(Structure):
    _fields_ = [
        ("id", c_uint32),
        ("flags", c_uint32),
        ("name", c_char_p),
        ("unit", c_char_p),
        ("description", c_char_p),
        ("default_value", c_double),
        ("min", c_double),
        ("max", c_double),
    ]


class OrientSample(Structure):
    _fields_ = [
        ("dt", c_double),
        ("gyro", OrientVec3),
        ("accel", OrientVec3),
        ("mag", OrientVec3),
        ("flags", c_uint32),
        ("reserved", c_uint32),
    ]


class OrientEuler(Structure):
    _fields_ = [("yaw", c_double), ("pitch", c_double), ("roll", c_double)]


class OrientDiagnostics(Structure):
    _fields_ = [
        ("present", c_uint32),
        ("reserved", c_uint32),
        ("gyro_bias", OrientVec3),
        ("rest", c_double),
        ("alpha", c_double),
        ("mu_ka", c_double),
        ("mu_km", c_double),
        ("mu_k", c_double),
        ("rate", OrientVec3),
        ("covariance", c_double * 10),
    ]


class OrientUncertainty(Structure):
    _fields_ = [
        ("present", c_uint32),
        ("reserved", c_uint32),
        ("heading", c_double),
        ("inclination", c_double),
    ]


#: OrientDiagnostics as a NumPy record: update_batch fills an array of these in place.
DIAGNOSTICS_DTYPE = np.dtype(
    [
        ("present", "=u4"),
        ("reserved", "=u4"),
        ("gyro_bias", "=f8", (3,)),
        ("rest", "=f8"),
        ("alpha", "=f8"),
        ("mu_ka", "=f8"),
        ("mu_km", "=f8"),
        ("mu_k", "=f8"),
        ("rate", "=f8", (3,)),
        ("covariance", "=f8", (10,)),
    ]
)
assert DIAGNOSTICS_DTYPE.itemsize == ctypes.sizeof(OrientDiagnostics)

_P = POINTER

# name: (restype, argtypes)
PROTOTYPES = {
    "orient_version": (c_char_p, []),
    "orient_abi_version": (c_uint32, []),
    "orient_status_message": (c_char_p, [c_int32]),
    "orient_last_error": (c_char_p, []),
    "orient_config_default": (c_int32, [c_int32, _P(OrientConfig)]),
    "orient_config_set_param": (c_int32, [_P(OrientConfig), c_uint32, c_double]),
    "orient_param_count": (c_int32, [c_int32, _P(c_uint32)]),
    "orient_param_info": (c_int32, [c_int32, c_uint32, _P(OrientParamInfo)]),
    "orient_param_find": (c_int32, [c_int32, c_char_p, _P(c_uint32)]),
    "orient_filter_new": (c_int32, [_P(OrientConfig), _P(c_void_p)]),
    "orient_filter_free": (c_int32, [c_void_p]),
    "orient_filter_kind": (c_int32, [c_void_p, _P(c_int32)]),
    "orient_filter_set_param": (c_int32, [c_void_p, c_uint32, c_double]),
    "orient_filter_get_param": (c_int32, [c_void_p, c_uint32, _P(c_double)]),
    "orient_filter_update": (c_int32, [c_void_p, _P(OrientSample)]),
    "orient_filter_update_arrays": (
        c_int32,
        [
            c_void_p,
            c_size_t,
            c_void_p,
            c_size_t,
            c_void_p,
            c_void_p,
            c_void_p,
            c_void_p,
            c_void_p,
            c_void_p,
            _P(c_size_t),
        ],
    ),
    "orient_smooth_config_default": (c_int32, [_P(OrientConfig)]),
    "orient_smooth_memory": (c_int32, [c_size_t, _P(c_size_t)]),
    "orient_smooth_arrays": (
        c_int32,
        [
            _P(OrientConfig),
            c_size_t,
            c_void_p,
            c_size_t,
            c_void_p,
            c_void_p,
            c_void_p,
            c_void_p,
            _P(c_size_t),
        ],
    ),
    "orient_filter_quaternion": (c_int32, [c_void_p, _P(OrientQuaternion)]),
    "orient_filter_euler": (c_int32, [c_void_p, _P(OrientEuler)]),
    "orient_filter_rotation_matrix": (c_int32, [c_void_p, _P(c_double)]),
    "orient_filter_gravity": (c_int32, [c_void_p, _P(OrientVec3)]),
    "orient_filter_linear_accel": (c_int32, [c_void_p, _P(OrientVec3)]),
    "orient_filter_linear_accel_earth": (c_int32, [c_void_p, _P(OrientVec3)]),
    "orient_filter_diagnostics": (c_int32, [c_void_p, c_void_p]),
    "orient_filter_uncertainty": (c_int32, [c_void_p, _P(OrientUncertainty)]),
    "orient_filter_state_size": (c_int32, [c_void_p, _P(c_size_t)]),
    "orient_filter_save": (c_int32, [c_void_p, _P(c_uint8), c_size_t, _P(c_size_t)]),
    "orient_filter_load": (c_int32, [c_void_p, _P(c_uint8), c_size_t]),
    "orient_filter_flags": (c_int32, [c_void_p, _P(c_uint32)]),
    "orient_filter_reset": (c_int32, [c_void_p]),
    "orient_filter_set_quaternion": (c_int32, [c_void_p, _P(OrientQuaternion)]),
    # issue 20: mounting, heading, declination, rig calibration
    "orient_filter_set_mounting": (c_int32, [c_void_p, _P(OrientQuaternion)]),
    "orient_filter_mounting": (c_int32, [c_void_p, _P(OrientQuaternion)]),
    "orient_filter_sensor_quaternion": (c_int32, [c_void_p, _P(OrientQuaternion)]),
    "orient_filter_set_heading": (c_int32, [c_void_p, c_double]),
    "orient_filter_reset_heading": (c_int32, [c_void_p]),
    "orient_filter_heading_offset": (c_int32, [c_void_p, _P(c_double)]),
    "orient_filter_set_declination": (c_int32, [c_void_p, c_double]),
    "orient_filter_declination": (c_int32, [c_void_p, _P(c_double)]),
    "orient_rig_calibrate": (c_int32, [_P(c_void_p), _P(OrientQuaternion), c_size_t, c_double]),
    "orient_rig_align_heading": (c_int32, [_P(c_void_p), _P(OrientQuaternion), c_size_t]),
    "orient_filter_set_sensor_model": (c_int32, [c_void_p, c_uint32, _P(OrientSensorModel)]),
    "orient_filter_sensor_model": (c_int32, [c_void_p, c_uint32, _P(OrientSensorModel)]),
    "orient_mag_calibrator_init": (c_int32, [_P(OrientMagCalibrator)]),
    "orient_mag_calibrator_add": (c_int32, [_P(OrientMagCalibrator), _P(OrientVec3)]),
    "orient_mag_calibrator_solve": (c_int32, [_P(OrientMagCalibrator), _P(OrientMagFit)]),
    "orient_mag_calibrator_rejected": (c_int32, [_P(OrientMagCalibrator), _P(c_uint64)]),
    "orient_gyro_offset": (c_int32, [_P(OrientVec3), c_size_t, _P(OrientSensorModel), _P(c_double)]),
}


def _library_path() -> Path:
    """ORIENT_LIBRARY if set, else the library bundled beside this file."""
    override = os.environ.get("ORIENT_LIBRARY")
    if override:
        return Path(override)
    names = {"win32": "orient.dll", "darwin": "liborient.dylib"}
    return Path(__file__).with_name(names.get(sys.platform, "liborient.so"))


def _load() -> ctypes.CDLL:
    path = _library_path()
    lib = ctypes.CDLL(str(path))
    for name, (restype, argtypes) in PROTOTYPES.items():
        fn = getattr(lib, name)
        fn.restype = restype
        fn.argtypes = argtypes
    if lib.orient_abi_version() != ABI_VERSION:
        raise ImportError(
            f"{path}: C ABI version {lib.orient_abi_version()}, this package needs {ABI_VERSION}"
        )
    return lib


lib = _load()
