//! The C types: plain `#[repr(C)]` data with fixed layout, and the constants of the header
//! that only the C API has (the flag and diagnostics bits are rendered from the core's
//! tables into `bits.rs`, the parameter slots into `param_ids.rs`).

use super::param_ids::ORIENT_MAX_PARAMS;
use core::ffi::c_char;

/// Version of the C ABI described by this header. It changes only when an existing
/// function, struct layout or constant changes meaning; additions keep it.
pub const ORIENT_ABI_VERSION: u32 = 1;

/// `OrientSample.flags`: the gyroscope field holds a reading (every filter needs one).
pub const ORIENT_SAMPLE_GYRO: u32 = 1;
/// `OrientSample.flags`: the accelerometer field holds a reading.
pub const ORIENT_SAMPLE_ACCEL: u32 = 2;
/// `OrientSample.flags`: the magnetometer field holds a reading.
pub const ORIENT_SAMPLE_MAG: u32 = 4;

/// `OrientParamInfo.flags`: 0 is also accepted and turns the feature off; `min` is the
/// smallest value that has it on.
pub const ORIENT_PARAM_FLAG_ZERO_OFF: u32 = 1;

/// OrientUncertainty.present: heading holds a value.
pub const ORIENT_UNCERTAINTY_HEADING: u32 = 1;
/// OrientUncertainty.present: inclination holds a value.
pub const ORIENT_UNCERTAINTY_INCLINATION: u32 = 2;

/// Result of every fallible call. Numbers are fixed and never reused. On any status but
/// ORIENT_STATUS_OK the call changed nothing (a batch keeps the samples before the bad
/// one), and orient_last_error() has the detail.
#[repr(i32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OrientStatus {
    /// Success.
    Ok = 0,
    /// A required pointer argument is NULL (checked before anything else).
    NullPointer = 1,
    /// The handle is not a live OrientFilter (OrientJoints): freed, or never returned by
    /// orient_filter_new (orient_joints_new), a copy of a handle's bytes included.
    InvalidHandle = 2,
    /// The kind is known but not built in this version of the library (reserved: every
    /// kind is built in this version).
    UnsupportedKind = 3,
    /// An enum value, flag bit or index that the library does not know.
    InvalidArgument = 4,
    /// The filter kind has no parameter with that id or name.
    UnknownParam = 5,
    /// A parameter value is not finite or outside its documented range.
    ParamOutOfRange = 6,
    /// A present sample field, or a given quaternion, holds NaN or +-Inf.
    NonFinite = 7,
    /// dt is below 1e-9 s (zero, negative, subnormal), above 1e6 s, NaN or infinite
    /// (a zero dt is a burst sample instead when ORIENT_PARAM_SAME_INSTANT is 1).
    InvalidDt = 8,
    /// An accelerometer, magnetometer or quaternion whose norm is zero (or so small
    /// that its square is not a normal double).
    ZeroVector = 9,
    /// A vector whose squared norm overflows a double, or a reading with a component at
    /// or beyond its physical bound: gyroscope 1e4 rad/s, accelerometer 1e5 m/s^2,
    /// magnetometer 1e12 (any unit).
    TooLarge = 10,
    /// A reading at or beyond the configured ORIENT_PARAM_*_RANGE (with
    /// ORIENT_PARAM_SATURATION_RECOVERY set to 1 the sample is used clipped instead and
    /// ORIENT_FLAG_SATURATED is set).
    Saturated = 11,
    /// The sample lacks a sensor the filter needs (every filter needs the gyroscope).
    MissingSensor = 12,
    /// The filter waits for its first accelerometer sample (ORIENT_INIT_ACC_MAG); with
    /// ORIENT_PARAM_SAME_INSTANT set to 1, for its first sample with dt > 0 as well. During
    /// a kind's start-up period (ORIENT_KIND_COMPLEMENTARY, ORIENT_KIND_GMVDK) a sample
    /// without an accelerometer reading is refused so too; a same-instant sample (dt 0) is
    /// not.
    NotInitialized = 13,
    /// The output needs data the filter has not received yet (linear acceleration
    /// before the first accelerometer sample).
    NoData = 14,
    /// The update would have produced a non-finite state. A guard: the bounds on dt and
    /// the readings keep accepted samples from reaching it.
    Numeric = 15,
    /// A count so large that the buffers it describes cannot exist; from
    /// orient_filter_new: 24576 filters are live already, the most the library holds.
    CountTooLarge = 16,
    /// `struct_size` does not match a configuration layout this library knows.
    VersionMismatch = 17,
    /// A bug: the library panicked. The panic was caught at the C boundary.
    Panic = 18,
    /// The output buffer is smaller than the data (orient_filter_save: see
    /// orient_filter_state_size).
    BufferTooSmall = 19,
    /// A state blob that is truncated, corrupted (checksum), of another format version or
    /// of another filter kind; the filter is unchanged.
    InvalidState = 20,
    /// A buffer the call needs could not be allocated; nothing was changed
    /// (orient_smooth_arrays: see orient_smooth_memory).
    OutOfMemory = 21,
    /// A joint of orient_joints_new names a segment the rig does not have, is its own
    /// child's parent, gives its child a second parent, closes a cycle, or has an axis
    /// that is NaN, infinite, or too short or too long to normalise; orient_last_error
    /// names the joint.
    InvalidJoint = 22,
}

/// Filter kinds, as the `kind` argument and `OrientConfig.kind`.
#[repr(i32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OrientKind {
    /// Madgwick 2010 gradient descent, IMU and MARG.
    Madgwick = 1,
    /// Mahony nonlinear complementary filter, IMU and MARG, bias estimate optional.
    Mahony = 2,
    /// McGinnis 2014 PI complementary filter: gains at rest only, start-up period (IMU).
    Complementary = 3,
    /// Kim & Golnaraghi 2004 quaternion EKF [q, omega, drift]; magnetometer heading optional.
    Ekf = 4,
    /// GMVDK 2024 double-SLERP filter with trust alpha and mu_K; start-up period.
    Gmvdk = 5,
    /// Recommended: strapdown with a quasi-inertial accelerometer low-pass, rest and motion
    /// gyro-bias estimation, magnetic disturbance rejection and hard-iron compensation.
    Robust = 6,
}

/// The one mapping between the core's kinds and the C numbers: code that iterates the
/// C kinds takes them from `Kind::ALL` through it, so a new kind is never left out.
impl From<crate::filters::Kind> for OrientKind {
    fn from(kind: crate::filters::Kind) -> OrientKind {
        use crate::filters::Kind;
        match kind {
            Kind::Madgwick => OrientKind::Madgwick,
            Kind::Mahony => OrientKind::Mahony,
            Kind::Complementary => OrientKind::Complementary,
            Kind::Ekf => OrientKind::Ekf,
            Kind::Gmvdk => OrientKind::Gmvdk,
            Kind::Robust => OrientKind::Robust,
        }
    }
}

/// Earth frames, as `OrientConfig.frame`.
#[repr(i32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OrientFrame {
    /// x East, y North, z Up (default).
    Enu = 0,
    /// x North, y East, z Down.
    Ned = 1,
    /// x North, y West, z Up.
    Nwu = 2,
}

/// Initial orientation, as `OrientConfig.init`.
#[repr(i32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OrientInit {
    /// From the first sample with an accelerometer (and magnetometer, if that sample has
    /// one); that sample is also used for a normal update (default).
    AccMag = 0,
    /// The identity orientation in the configured frame.
    Identity = 1,
    /// `OrientConfig.initial`, in the configured frame (normalised).
    Given = 2,
}

/// A 3-vector.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct OrientVec3 {
    pub x: f64,
    pub y: f64,
    pub z: f64,
}

/// A Hamilton quaternion, scalar first. As an orientation it maps sensor to earth
/// coordinates: v_earth = q * v_sensor * conj(q).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct OrientQuaternion {
    pub w: f64,
    pub x: f64,
    pub y: f64,
    pub z: f64,
}

/// Euler angles, radians, intrinsic Z-Y'-X'': R = Rz(yaw) * Ry(pitch) * Rx(roll).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct OrientEuler {
    /// About the earth z axis, (-pi, pi].
    pub yaw: f64,
    /// [-pi/2, pi/2].
    pub pitch: f64,
    /// (-pi, pi].
    pub roll: f64,
}

/// One sensor sample (88 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct OrientSample {
    /// Seconds since the previous sample; finite, at least 1e-9 and at most 1e6.
    pub dt: f64,
    /// Angular rate, rad/s, sensor frame.
    pub gyro: OrientVec3,
    /// Specific force, m/s^2, sensor frame (reads about +9.81 along "up" at rest).
    pub accel: OrientVec3,
    /// Magnetic field, any unit consistent over the run (uT in the examples).
    pub mag: OrientVec3,
    /// ORIENT_SAMPLE_* bits saying which fields hold readings; other bits must be 0.
    /// Fields whose bit is clear are ignored, whatever they hold.
    pub flags: u32,
    /// Must be 0.
    pub reserved: u32,
}

/// A filter configuration (1072 bytes). Fill it with orient_config_default(), then
/// change fields or parameters.
///
/// Compatibility rule: `struct_size` is set by orient_config_default() to the size
/// this header describes. Later versions of the library only append fields and give
/// new parameters new slots in `params`; they accept every `struct_size` an earlier
/// header wrote. This version accepts exactly sizeof(OrientConfig) and returns
/// ORIENT_STATUS_VERSION_MISMATCH otherwise.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct OrientConfig {
    /// sizeof(OrientConfig) as the caller compiled it.
    pub struct_size: u32,
    /// One of ORIENT_KIND_*.
    pub kind: i32,
    /// One of ORIENT_FRAME_*; the frame every output is expressed in.
    pub frame: i32,
    /// One of ORIENT_INIT_*.
    pub init: i32,
    /// Initial orientation for ORIENT_INIT_GIVEN.
    pub initial: OrientQuaternion,
    /// Parameter values by slot (ORIENT_PARAM_*). Slots the kind does not use are
    /// ignored; list a kind's slots with orient_param_count() / orient_param_info().
    pub params: [f64; ORIENT_MAX_PARAMS],
}

/// What one parameter means, for hosts that list settings (an inspector, a CLI).
/// The strings are static, NUL-terminated UTF-8, and live as long as the library.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct OrientParamInfo {
    /// Slot in OrientConfig.params (a joint parameter's: its index,
    /// orient_joint_param_info).
    pub id: u32,
    /// ORIENT_PARAM_FLAG_* bits.
    pub flags: u32,
    /// Identifier, e.g. "beta_imu".
    pub name: *const c_char,
    /// Unit, e.g. "rad/s"; "1" for dimensionless.
    pub unit: *const c_char,
    /// Meaning and the source of the default.
    pub description: *const c_char,
    pub default_value: f64,
    /// Smallest accepted value (inclusive), besides 0 where ORIENT_PARAM_FLAG_ZERO_OFF
    /// is set. Subnormal values are never accepted.
    pub min: f64,
    /// Largest accepted value (inclusive).
    pub max: f64,
}

/// Internal states for display, the same struct for every kind. A field whose
/// ORIENT_DIAG_* bit is clear in `present` does not apply (to this kind, or yet) and
/// holds NaN; it is never a made-up zero.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct OrientDiagnostics {
    /// ORIENT_DIAG_* bits of the fields that hold values.
    pub present: u32,
    /// Always 0.
    pub reserved: u32,
    /// Gyroscope bias being subtracted, rad/s, sensor frame (Mahony b, complementary
    /// omega_b, EKF drift delta, GMVDK regression bias, the robust kind's estimate,
    /// Madgwick's with its rest-bias option on).
    pub gyro_bias: OrientVec3,
    /// 1 when the last sample counted as rest, else 0 (complementary: gains on; robust:
    /// its rest detector; EKF, Madgwick and Mahony: with their rest options on).
    pub rest: f64,
    /// GMVDK accelerometer trust alpha, [0, 1].
    pub alpha: f64,
    /// GMVDK magnetometer angle trust mu_KA, [0, 1].
    pub mu_ka: f64,
    /// GMVDK magnetometer magnitude trust mu_KM, [0, 1].
    pub mu_km: f64,
    /// GMVDK magnetometer trust mu_K = mu_2 * alpha, [0, 1].
    pub mu_k: f64,
    /// EKF angular-rate state, rad/s, sensor frame.
    pub rate: OrientVec3,
    /// EKF covariance diagonal, state order [q0, q1, q2, q3, omega_xyz, drift_xyz]
    /// (the quaternion in the filter's native North-East-Down frame).
    pub covariance: [f64; 10],
}

/// One standard deviation of the orientation's error, radians, from the kinds that model
/// it (orient_filter_uncertainty). A field whose ORIENT_UNCERTAINTY_* bit in `present` is
/// clear holds NaN.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct OrientUncertainty {
    /// ORIENT_UNCERTAINTY_* bits of the fields that hold values.
    pub present: u32,
    /// 0.
    pub reserved: u32,
    /// Heading error about the earth's vertical: EKF from its covariance; robust from its
    /// heading error model, growing while the magnetometer is distrusted or absent and
    /// settling while it is used (orient_filter_uncertainty says to what).
    pub heading: f64,
    /// Inclination error (tilt of the estimated vertical): EKF, from its covariance.
    pub inclination: f64,
}
