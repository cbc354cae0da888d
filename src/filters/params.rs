//! Tunable parameters: one numbered slot per setting, described by a static table so
//! that hosts (a Unity inspector, the replay tool's `--set`) can list and set them by
//! name without knowing each filter.
//!
//! Slots 0-7 are common to every kind; each kind has its own block (Madgwick 8-15,
//! Mahony 16-23, complementary 24-39, EKF 40-55, GMVDK 56-79, robust 80-103; 104-127 free). A slot
//! number is never reused for a different meaning.

/// Number of parameter slots in a configuration.
pub const MAX_PARAMS: usize = 128;

/// Slot numbers. Common slots first, then one block per kind.
pub mod id {
    /// Magnitude of gravity used for the gravity and linear-acceleration outputs.
    pub const GRAVITY: u32 = 0;
    /// Gyroscope full-scale range; readings at or beyond it are rejected as saturated.
    pub const GYRO_RANGE: u32 = 1;
    /// Accelerometer full-scale range; readings at or beyond it are rejected as saturated.
    pub const ACCEL_RANGE: u32 = 2;
    /// The longest dt taken as given; a larger one is a gap, re-acquired (see `GAP` flag).
    pub const GAP_DT: u32 = 3;
    /// Saturation policy (issue 20): 0 rejects a saturated sample, 1 uses it clipped and
    /// recovers.
    pub const SATURATION_RECOVERY: u32 = 4;
    /// Burst policy for dt = 0 (issue 20): 0 rejects it, 1 takes it as the same instant.
    pub const SAME_INSTANT: u32 = 5;

    /// Madgwick β for steps without a magnetometer.
    pub const MADGWICK_BETA_IMU: u32 = 8;
    /// Madgwick β for steps with a magnetometer.
    pub const MADGWICK_BETA_MARG: u32 = 9;
    /// Madgwick: time constant of the gyro bias learned at rest (0 = off).
    pub const MADGWICK_REST_BIAS_TAU: u32 = 10;

    pub const MAHONY_KP: u32 = 16;
    pub const MAHONY_KI: u32 = 17;
    pub const MAHONY_REST_BIAS_TAU: u32 = 18;

    pub const COMPLEMENTARY_KP: u32 = 24;
    pub const COMPLEMENTARY_KI: u32 = 25;
    pub const COMPLEMENTARY_GYRO_REST: u32 = 26;
    pub const COMPLEMENTARY_ACCEL_REST: u32 = 27;
    pub const COMPLEMENTARY_INIT_DURATION: u32 = 28;
    pub const COMPLEMENTARY_ALIGN_HEADING: u32 = 29;

    pub const EKF_TAU_OMEGA: u32 = 40;
    pub const EKF_OMEGA_STD: u32 = 41;
    pub const EKF_TAU_DRIFT: u32 = 42;
    pub const EKF_DRIFT_STD: u32 = 43;
    pub const EKF_GYRO_NOISE: u32 = 44;
    pub const EKF_ACCEL_NOISE: u32 = 45;
    pub const EKF_ACCEL_MOTION: u32 = 46;
    pub const EKF_HEADING_STD: u32 = 47;
    pub const EKF_MOTION_TAU: u32 = 48;
    pub const EKF_HEADING_TAU: u32 = 49;
    pub const EKF_REST_RATE_STD: u32 = 50;
    pub const EKF_ACCEL_ADAPT_TAU: u32 = 51;
    pub const EKF_HEADING_ADAPT_TAU: u32 = 52;

    pub const GMVDK_SLOPE_ALPHA: u32 = 56;
    pub const GMVDK_SLOPE_MUK: u32 = 57;
    pub const GMVDK_MU_WINDOW: u32 = 58;
    pub const GMVDK_INIT_DURATION: u32 = 59;
    pub const GMVDK_ACTIVITY_TAU: u32 = 60;
    pub const GMVDK_GYRO_ACTIVITY: u32 = 61;
    pub const GMVDK_ACCEL_ACTIVITY: u32 = 62;
    pub const GMVDK_BIAS_WINDOW: u32 = 63;
    pub const GMVDK_STATIC_ALPHA: u32 = 64;
    pub const GMVDK_RELATIVE_OUTPUT: u32 = 65;

    pub const ROBUST_TAU_ACC: u32 = 80;
    pub const ROBUST_TAU_MAG: u32 = 81;
    pub const ROBUST_REST_GYRO: u32 = 82;
    pub const ROBUST_REST_ACCEL: u32 = 83;
    pub const ROBUST_REST_TIME: u32 = 84;
    pub const ROBUST_REST_TAU: u32 = 85;
    pub const ROBUST_BIAS_TAU_REST: u32 = 86;
    pub const ROBUST_BIAS_TAU_MOTION: u32 = 87;
    pub const ROBUST_BIAS_LIMIT: u32 = 88;
    pub const ROBUST_MAG_NORM_TH: u32 = 89;
    pub const ROBUST_MAG_DIP_TH: u32 = 90;
    pub const ROBUST_HARD_IRON_TIME: u32 = 91;
    pub const ROBUST_REST_TILT: u32 = 92;
}

/// What one parameter slot means.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParamSpec {
    /// Slot number in [`crate::Config`] (see [`id`]).
    pub id: u32,
    /// Lower-case identifier, e.g. `beta_imu`.
    pub name: &'static str,
    /// Unit, e.g. `rad/s`; `1` for a dimensionless value.
    pub unit: &'static str,
    /// One sentence: meaning, and where the default comes from.
    pub doc: &'static str,
    pub default: f64,
    /// Smallest accepted value (inclusive), besides the 0 that `zero_off` allows.
    pub min: f64,
    /// Largest accepted value (inclusive).
    pub max: f64,
    /// 0 is also accepted and turns the feature off; `min` is then the smallest value
    /// that has it on (smaller ones would mean no filter, only broken arithmetic).
    pub zero_off: bool,
}

impl ParamSpec {
    /// True when `value` is finite and within `[min, max]`, or 0 where that turns the
    /// feature off. Subnormal values are never accepted (a ±0 is a 0).
    pub fn accepts(&self, value: f64) -> bool {
        let zero = value == 0.0;
        let normal = zero || value.abs() >= f64::MIN_POSITIVE;
        value.is_finite() && normal && ((zero && self.zero_off) || (value >= self.min && value <= self.max))
    }

    /// The smallest positive value accepted: `min`, or the smallest normal number for a
    /// range that starts at 0.
    pub fn smallest_positive(&self) -> f64 {
        if self.min > 0.0 {
            self.min
        } else {
            f64::MIN_POSITIVE
        }
    }
}

/// The settings every kind has.
pub const COMMON: [ParamSpec; 6] = [
    ParamSpec {
        id: id::GRAVITY,
        name: "gravity",
        unit: "m/s^2",
        doc: "Gravity magnitude for the gravity and linear-acceleration outputs; default: \
              standard gravity 9.80665 (CGPM 1901).",
        default: 9.80665,
        min: 1e-3,
        max: 1e3,
        zero_off: false,
    },
    ParamSpec {
        id: id::GYRO_RANGE,
        name: "gyro_range",
        unit: "rad/s",
        doc: "Gyroscope full scale: a sample with any axis at or beyond it is rejected as \
              saturated; 0 turns the check off (default, since the range is the sensor's).",
        default: 0.0,
        min: 0.1,
        max: 1e4,
        zero_off: true,
    },
    ParamSpec {
        id: id::ACCEL_RANGE,
        name: "accel_range",
        unit: "m/s^2",
        doc: "Accelerometer full scale: a sample with any axis at or beyond it is rejected as \
              saturated; 0 turns the check off (default).",
        default: 0.0,
        min: 1.0,
        max: 1e5,
        zero_off: true,
    },
    ParamSpec {
        id: id::GAP_DT,
        name: "gap_dt",
        unit: "s",
        doc: "Longest dt taken as given: a larger dt is a gap in the data (dropped packets), and \
              the update re-acquires the orientation from the sensors instead of integrating \
              over it (GAP and REACQUIRED flags); default 0.25 (orient: over a quarter second \
              a hand's rate changes enough that integrating the next sample's rate errs more \
              than one accelerometer reading; 10 periods of a 40 Hz sensor); 0 turns it off.",
        default: 0.25,
        min: 1e-3,
        max: 1e6,
        zero_off: true,
    },
    ParamSpec {
        id: id::SATURATION_RECOVERY,
        name: "saturation_recovery",
        unit: "1",
        doc: "What a reading at or beyond gyro_range or accel_range does: 0 (default) rejects the \
              sample as saturated; 1 uses it clipped (a gyroscope reading clipped just under \
              the range, a saturated accelerometer reading left out), sets the SATURATED flag, \
              and after gyroscope saturation re-acquires the orientation from the next \
              unsaturated sample with an accelerometer reading (x-io Fusion's angular-rate \
              recovery). The physical bounds stay errors.",
        default: 0.0,
        min: 1.0,
        max: 1.0,
        zero_off: true,
    },
    ParamSpec {
        id: id::SAME_INSTANT,
        name: "same_instant",
        unit: "1",
        doc: "What a sample with dt = 0 does (bursts of packets with one timestamp): 0 \
              (default) rejects it as an invalid dt; 1 takes it as the same instant as the \
              next sample with dt > 0: nothing is integrated then, its gyroscope reading is \
              averaged with the following ones up to and including that sample, which \
              integrates the average over its dt, so no rotation is lost (the SAME_INSTANT \
              flag is set). Its accelerometer and magnetometer readings are not used.",
        default: 0.0,
        min: 1.0,
        max: 1.0,
        zero_off: true,
    },
];
