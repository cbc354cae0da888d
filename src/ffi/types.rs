//! The C types: plain `#[repr(C)]` data with fixed layout, and the constants of the header.

use core::ffi::c_char;

/// Version of the C ABI described by this header. It changes only when an existing
/// function, struct layout or constant changes meaning; additions keep it.
pub const ORIENT_ABI_VERSION: u32 = 1;

/// Number of parameter slots in `OrientConfig.params`.
pub const ORIENT_MAX_PARAMS: usize = 64;

/// `OrientSample.flags`: the gyroscope field holds a reading (every filter needs one).
pub const ORIENT_SAMPLE_GYRO: u32 = 1;
/// `OrientSample.flags`: the accelerometer field holds a reading.
pub const ORIENT_SAMPLE_ACCEL: u32 = 2;
/// `OrientSample.flags`: the magnetometer field holds a reading.
pub const ORIENT_SAMPLE_MAG: u32 = 4;

/// `orient_filter_flags`: the filter has an orientation (clear while it waits for its
/// first accelerometer sample under `ORIENT_INIT_ACC_MAG`).
pub const ORIENT_FLAG_INITIALIZED: u32 = 1;
/// `orient_filter_flags`: the last accepted update used the accelerometer.
pub const ORIENT_FLAG_ACCEL_USED: u32 = 2;
/// `orient_filter_flags`: the last accepted update used the magnetometer.
pub const ORIENT_FLAG_MAG_USED: u32 = 4;

/// Parameter slot (every kind): gravity magnitude for the gravity and linear
/// acceleration outputs, m/s^2, default 9.80665.
pub const ORIENT_PARAM_GRAVITY: u32 = 0;
/// Parameter slot (every kind): gyroscope full scale, rad/s; a sample with any axis at or
/// beyond it is rejected with ORIENT_STATUS_SATURATED. Default 0 = no check.
pub const ORIENT_PARAM_GYRO_RANGE: u32 = 1;
/// Parameter slot (every kind): accelerometer full scale, m/s^2; a sample with any axis
/// at or beyond it is rejected with ORIENT_STATUS_SATURATED. Default 0 = no check.
pub const ORIENT_PARAM_ACCEL_RANGE: u32 = 2;
/// Parameter slot (Madgwick): beta for steps without magnetometer, rad/s, default 0.041
/// (Madgwick 2010, section V). beta = sqrt(3/4) * max gyro error, eq. (33):
/// see orient_madgwick_beta().
pub const ORIENT_PARAM_MADGWICK_BETA_IMU: u32 = 8;
/// Parameter slot (Madgwick): beta for steps with magnetometer, rad/s, default 0.033
/// (Madgwick 2010, section V).
pub const ORIENT_PARAM_MADGWICK_BETA_MARG: u32 = 9;

/// Result of every fallible call. Numbers are fixed and never reused. On any status but
/// ORIENT_STATUS_OK the call changed nothing (a batch keeps the samples before the bad
/// one), and orient_last_error() has the detail.
#[repr(i32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OrientStatus {
    /// Success.
    Ok = 0,
    /// A required pointer argument is NULL.
    NullPointer = 1,
    /// The handle is not a live OrientFilter (freed, foreign or misaligned pointer).
    InvalidHandle = 2,
    /// The kind is known but not built in this version of the library.
    UnsupportedKind = 3,
    /// An enum value, flag bit or index that the library does not know.
    InvalidArgument = 4,
    /// The filter kind has no parameter with that id or name.
    UnknownParam = 5,
    /// A parameter value is not finite or outside its documented range.
    ParamOutOfRange = 6,
    /// A present sample field, or a given quaternion, holds NaN or +-Inf.
    NonFinite = 7,
    /// dt is zero, negative, NaN or infinite.
    InvalidDt = 8,
    /// An accelerometer, magnetometer or quaternion whose norm is zero (or so small
    /// that its square is not a normal double).
    ZeroVector = 9,
    /// A vector whose squared norm overflows a double.
    TooLarge = 10,
    /// A reading at or beyond the configured ORIENT_PARAM_*_RANGE.
    Saturated = 11,
    /// The sample lacks a sensor the filter needs (every filter needs the gyroscope).
    MissingSensor = 12,
    /// The filter waits for its first accelerometer sample (ORIENT_INIT_ACC_MAG).
    NotInitialized = 13,
    /// The output needs data the filter has not received yet (linear acceleration
    /// before the first accelerometer sample).
    NoData = 14,
    /// The update would have produced a non-finite orientation (e.g. an enormous dt).
    Numeric = 15,
    /// A count so large that the buffers it describes cannot exist.
    CountTooLarge = 16,
    /// `struct_size` does not match a configuration layout this library knows.
    VersionMismatch = 17,
    /// A bug: the library panicked. The panic was caught at the C boundary.
    Panic = 18,
}

/// Filter kinds, as the `kind` argument and `OrientConfig.kind`.
#[repr(i32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OrientKind {
    /// Madgwick 2010 gradient descent, IMU and MARG.
    Madgwick = 1,
    /// Mahony nonlinear complementary filter (not built yet: ORIENT_STATUS_UNSUPPORTED_KIND).
    Mahony = 2,
    /// McGinnis 2014 PI complementary filter (not built yet).
    Complementary = 3,
    /// Kim & Golnaraghi 2004 quaternion EKF (not built yet).
    Ekf = 4,
    /// GMVDK 2024 double-SLERP filter (not built yet).
    Gmvdk = 5,
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
    /// Seconds since the previous sample; finite and > 0.
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

/// A filter configuration (560 bytes). Fill it with orient_config_default(), then
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
    /// Slot in OrientConfig.params.
    pub id: u32,
    /// Always 0.
    pub reserved: u32,
    /// Identifier, e.g. "beta_imu".
    pub name: *const c_char,
    /// Unit, e.g. "rad/s"; "1" for dimensionless.
    pub unit: *const c_char,
    /// Meaning and the source of the default.
    pub description: *const c_char,
    pub default_value: f64,
    /// Smallest accepted value (inclusive).
    pub min: f64,
    /// Largest accepted value (inclusive).
    pub max: f64,
}
