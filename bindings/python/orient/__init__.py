"""orient: IMU/MARG orientation filters (Madgwick, Mahony, McGinnis complementary,
Kim-Golnaraghi EKF, GMVDK and the recommended ``Robust``) over orient's C library.

Conventions: earth frame ENU by default (NED, NWU selectable); Hamilton quaternions
(w, x, y, z) mapping sensor to earth; gyroscope rad/s, accelerometer m/s^2,
magnetometer any unit; float64; dt in seconds with every sample.

Example (``gyr``, ``acc``, ``mag``: (N, 3) NumPy arrays)::

    import orient
    f = orient.Robust(tau_acc=3.0)
    r = f.update_batch(gyr, acc, mag, dt=0.01)
    r.quaternion, r.flags, r.diagnostics["gyro_bias"]
"""

from ._filter import (
    DIAGNOSTICS_DTYPE,
    BatchResult,
    Complementary,
    Ekf,
    Filter,
    Gmvdk,
    MagCalibrator,
    MagFit,
    Madgwick,
    Mahony,
    OrientError,
    ParamInfo,
    Robust,
    align_rig_heading,
    calibrate_rig,
    calibrate_rig_each,
    gyro_offset,
    params,
    smooth,
    smooth_memory,
    status_message,
    version,
)
from ._joints import (SAMPLE_DTYPE, Joint, JointAxes, Joints, estimate_hinge_axes, estimate_two_dof_axes,
                      joint_params, run_rig)
from ._native import (
    FLAG_ACCEL_REJECTED,
    FLAG_ACCEL_USED,
    FLAG_GAP,
    FLAG_INITIALIZED,
    FLAG_MAG_DISTURBED,
    FLAG_MAG_REJECTED,
    FLAG_MAG_USED,
    FLAG_REACQUIRE_PENDING,
    FLAG_SAME_INSTANT,
    FLAG_SATURATED,
    FLAG_REACQUIRED,
    FLAG_REST,
    Frame,
    Kind,
    Status,
)

__version__ = version()

__all__ = [
    "align_rig_heading",
    "estimate_hinge_axes",
    "estimate_two_dof_axes",
    "JointAxes",
    "Joint",
    "Joints",
    "joint_params",
    "run_rig",
    "SAMPLE_DTYPE",
    "calibrate_rig",
    "calibrate_rig_each",
    "gyro_offset",
    "MagCalibrator",
    "MagFit",
    "BatchResult",
    "Complementary",
    "DIAGNOSTICS_DTYPE",
    "Ekf",
    "FLAG_ACCEL_REJECTED",
    "FLAG_ACCEL_USED",
    "FLAG_GAP",
    "FLAG_INITIALIZED",
    "FLAG_MAG_DISTURBED",
    "FLAG_MAG_REJECTED",
    "FLAG_MAG_USED",
    "FLAG_REACQUIRE_PENDING",
    "FLAG_SAME_INSTANT",
    "FLAG_SATURATED",
    "FLAG_REACQUIRED",
    "FLAG_REST",
    "Filter",
    "Frame",
    "Gmvdk",
    "Kind",
    "Madgwick",
    "Mahony",
    "OrientError",
    "ParamInfo",
    "Robust",
    "Status",
    "params",
    "smooth",
    "smooth_memory",
    "status_message",
    "version",
]
