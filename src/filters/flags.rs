//! State flags reported by [`crate::Filter::flags`].

/// The filter has an orientation (always set unless waiting for acc/mag init).
pub const INITIALIZED: u32 = 1;
/// The last accepted update used the accelerometer.
pub const ACCEL_USED: u32 = 2;
/// The last accepted update used the magnetometer.
pub const MAG_USED: u32 = 4;
/// The last accepted update followed a gap: its dt was above `gap_dt`. Nothing was
/// integrated over the gap (the motion in it is unknown): the update re-acquired the
/// orientation from the sensors ([`REACQUIRED`]) or, without an accelerometer
/// reading, held it ([`REACQUIRE_PENDING`]).
pub const GAP: u32 = 8;
/// The last accepted update re-acquired the orientation after a gap: inclination from
/// the accelerometer, heading from the magnetometer when the sample has one (and the
/// kind accepts it), else the heading held before the gap; the kind's internal
/// low-passes and detectors started over, its bias estimate was kept.
pub const REACQUIRED: u32 = 16;
/// A gap ended on a sample without an accelerometer reading: the orientation is held
/// (then integrated from the gyroscope) until the next sample that has one, which
/// re-acquires it.
pub const REACQUIRE_PENDING: u32 = 32;
/// Every bit above.
pub const ALL: u32 = INITIALIZED | ACCEL_USED | MAG_USED | GAP | REACQUIRED | REACQUIRE_PENDING;
