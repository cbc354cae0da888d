//! State flags reported by [`crate::Filter::flags`].

/// The filter has an orientation: clear while it waits for its first accelerometer
/// sample, and through a kind's own start-up period (complementary, GMVDK), whose
/// samples set [`ACCEL_USED`] (and [`MAG_USED`] or [`MAG_REJECTED`]).
pub const INITIALIZED: u32 = 1;
/// The last accepted update used the accelerometer.
pub const ACCEL_USED: u32 = 2;
/// The last accepted update used the magnetometer.
pub const MAG_USED: u32 = 4;
/// The last accepted update followed a gap: its dt was above `gap_dt`. Nothing was
/// integrated over the gap (the motion in it is unknown): the update re-acquired the
/// orientation from the sensors ([`REACQUIRED`]) or, without an accelerometer
/// reading, held it ([`REACQUIRE_PENDING`]); during an own start-up period the period
/// started over with the sample (not at a gap right after a gap).
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
/// The last accepted sample had an accelerometer reading that the update did not use: the
/// kind's own test turned it down (robust's and the EKF's adaptive gating, GMVDK's
/// trust, McGinnis' rest gate) or it only re-acquires.
pub const ACCEL_REJECTED: u32 = 64;
/// The last accepted sample had a magnetometer reading that the update did not use (the
/// kind has no heading correction, the field defines no north, or the kind turned it down).
pub const MAG_REJECTED: u32 = 128;
/// The kind counts the magnetic field as disturbed now (robust: the last reading failed
/// the norm and dip tests, hard iron compensated). Read from the state, not stored.
pub const MAG_DISTURBED: u32 = 256;
/// The kind counts the sensor as resting now (McGinnis' and the robust kind's rest
/// detection; the EKF, Madgwick and Mahony with their rest options on). Read from the
/// state, not stored.
pub const REST: u32 = 512;
/// The last accepted update had a reading at or beyond its configured range, used
/// clipped (`saturation_recovery` = 1): a gyroscope reading clipped just under the
/// range, an accelerometer reading left out. After gyroscope saturation
/// [`REACQUIRE_PENDING`] is set: the next unsaturated sample with an accelerometer
/// reading re-acquires the orientation.
pub const SATURATED: u32 = 1024;
/// The last accepted sample had dt = 0 and was taken as the same instant as the next
/// sample with dt > 0 (`same_instant` = 1): nothing was integrated, its gyroscope
/// reading waits to be averaged into that sample's step.
pub const SAME_INSTANT: u32 = 2048;
/// The bits an update stores (the others are read from the state).
pub(crate) const STORED: u32 = INITIALIZED
    | ACCEL_USED
    | MAG_USED
    | GAP
    | REACQUIRED
    | REACQUIRE_PENDING
    | ACCEL_REJECTED
    | MAG_REJECTED
    | SATURATED
    | SAME_INSTANT;
/// Every bit above.
pub const ALL: u32 = STORED | MAG_DISTURBED | REST;
