//! Flag and diagnostics bits for C. Generated from the core's tables (the `bits!` tables
//! of `filters::flags` and `filters::diag`) by the test `bits_are_generated_from_the_tables`
//! in `src/ffi/render.rs`; do not edit. Regenerate: ORIENT_BLESS=1 cargo test -p orient --lib
//! generated_from_the_tables

/// `orient_filter_flags`: the filter has an orientation. Clear while it waits for its
/// first accelerometer sample (the default initialisation, from the accelerometer and
/// magnetometer), and through the start-up period of the complementary and GMVDK kinds,
/// ORIENT_PARAM_*_INIT_DURATION seconds of samples with an accelerometer reading: their
/// readings are averaged into the initial orientation, and each such sample sets
/// ORIENT_FLAG_ACCEL_USED and, for the magnetometer, ORIENT_FLAG_MAG_USED or
/// ORIENT_FLAG_MAG_REJECTED as the period will use it; the dt = 0 samples of
/// ORIENT_PARAM_SAME_INSTANT are samples of the period too.
pub const ORIENT_FLAG_INITIALIZED: u32 = 1;
/// `orient_filter_flags`: the last accepted update used the accelerometer.
pub const ORIENT_FLAG_ACCEL_USED: u32 = 2;
/// `orient_filter_flags`: the last accepted update used the magnetometer.
pub const ORIENT_FLAG_MAG_USED: u32 = 4;
/// `orient_filter_flags`: the last accepted update followed a gap (dt above
/// ORIENT_PARAM_GAP_DT). Nothing was integrated over the gap, whose motion is unknown:
/// the update re-acquired the orientation (ORIENT_FLAG_REACQUIRED) or, on a sample
/// without an accelerometer reading, held it (ORIENT_FLAG_REACQUIRE_PENDING). During the
/// start-up period of the complementary and GMVDK kinds the period started over with the
/// sample instead (not at a gap right after a gap: where every sample is one, it goes on,
/// and its stillness test alone starts it over).
pub const ORIENT_FLAG_GAP: u32 = 8;
/// `orient_filter_flags`: the last accepted update re-acquired the orientation (after a
/// gap, a gyroscope saturation or the rest watch, see ORIENT_FLAG_REACQUIRE_PENDING):
/// inclination from its accelerometer reading, heading from its magnetometer reading when
/// it has one (every kind but the robust one, whose magnetic disturbance test may refuse
/// the reading, and the complementary one, which uses it only with
/// ORIENT_PARAM_COMPLEMENTARY_ALIGN_HEADING), else the heading held before. The kind's
/// low-passes and detectors start over; its bias estimate is kept, but after the rest
/// watch the still sample's gyroscope reading becomes the bias of every kind that learns
/// one or still subtracts one (the complementary filter's rest reference ω_b0 too).
pub const ORIENT_FLAG_REACQUIRED: u32 = 16;
/// `orient_filter_flags`: the next sample with an accelerometer reading re-acquires the
/// orientation (ORIENT_FLAG_REACQUIRED); until then it is integrated from the gyroscope.
/// Set when a gap ends on a sample without an accelerometer reading (the orientation is
/// held over the gap), after gyroscope saturation, and by the rest watch: when the sensor
/// lies still (gyroscope below 3 °/s, accelerometer norm within 5 % of the configured
/// gravity) and the estimate's vertical has been more than 10° from the accelerometer's,
/// or the kind's bias more than 6 °/s from the gyroscope's reading, for 5 s net of the
/// time it was not (looked at every 128th sample, at least four looks; a look at a moving
/// sensor starts the count over). An estimate can rest there at a stationary point of its
/// kind's correction (Madgwick's and Mahony's magnetometer terms near a 180° heading
/// error, the EKF's gravity update near an upside-down estimate), or spin on a wrong bias
/// that its kind then cannot learn (GMVDK distrusts the accelerometer while the de-biased
/// rate is large, the complementary filter's rest test compares with its start-up bias).
pub const ORIENT_FLAG_REACQUIRE_PENDING: u32 = 32;
/// `orient_filter_flags`: the last accepted sample had an accelerometer reading that the
/// update did not use (the kind's own test turned it down, e.g. the robust kind's and the
/// EKF's gating of linear acceleration, GMVDK's trust, McGinnis' rest gate).
pub const ORIENT_FLAG_ACCEL_REJECTED: u32 = 64;
/// `orient_filter_flags`: the last accepted sample had a magnetometer reading that the
/// update did not use (the kind has no heading correction, the field defines no north, or
/// the kind turned it down).
pub const ORIENT_FLAG_MAG_REJECTED: u32 = 128;
/// `orient_filter_flags`: the kind counts the magnetic field as disturbed now (the robust
/// kind: the last reading failed its norm and dip tests, hard iron compensated). Read
/// from the state, not stored.
pub const ORIENT_FLAG_MAG_DISTURBED: u32 = 256;
/// `orient_filter_flags`: the kind counts the sensor as resting now (McGinnis' and the
/// robust kind's rest detection; the EKF, Madgwick and Mahony with their rest options on,
/// ORIENT_PARAM_EKF_REST_RATE_STD and ORIENT_PARAM_*_REST_BIAS_TAU; GMVDK never sets it).
/// Read from the state, not stored.
pub const ORIENT_FLAG_REST: u32 = 512;
/// `orient_filter_flags`: the last update had a reading at or beyond its configured range
/// and used it clipped (ORIENT_PARAM_SATURATION_RECOVERY = 1): a gyroscope reading
/// clipped just under the range, an accelerometer reading left out. After gyroscope
/// saturation ORIENT_FLAG_REACQUIRE_PENDING is set too: the next unsaturated sample with
/// an accelerometer reading re-acquires the orientation (ORIENT_FLAG_REACQUIRED).
pub const ORIENT_FLAG_SATURATED: u32 = 1024;
/// `orient_filter_flags`: the last sample had dt = 0 and was taken as the same instant as
/// the next sample with dt > 0 (ORIENT_PARAM_SAME_INSTANT = 1): nothing was integrated;
/// its gyroscope reading is averaged into that sample's step.
pub const ORIENT_FLAG_SAME_INSTANT: u32 = 2048;

/// OrientDiagnostics.present: gyro_bias holds a value.
pub const ORIENT_DIAG_GYRO_BIAS: u32 = 1;
/// OrientDiagnostics.present: rest holds a value.
pub const ORIENT_DIAG_REST: u32 = 2;
/// OrientDiagnostics.present: alpha holds a value.
pub const ORIENT_DIAG_ALPHA: u32 = 4;
/// OrientDiagnostics.present: mu_ka holds a value.
pub const ORIENT_DIAG_MU_KA: u32 = 8;
/// OrientDiagnostics.present: mu_km holds a value.
pub const ORIENT_DIAG_MU_KM: u32 = 16;
/// OrientDiagnostics.present: mu_k holds a value.
pub const ORIENT_DIAG_MU_K: u32 = 32;
/// OrientDiagnostics.present: rate holds a value.
pub const ORIENT_DIAG_RATE: u32 = 64;
/// OrientDiagnostics.present: covariance holds values.
pub const ORIENT_DIAG_COVARIANCE: u32 = 128;
