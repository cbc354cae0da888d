//! State flags reported by [`crate::Filter::flags`].
//!
//! Each bit is written once, in the `bits!` table below: its value and the one text that
//! documents it here and, as `ORIENT_FLAG_*`, in the C header (`src/ffi/bits.rs` is
//! rendered from this table and checked by a test; see `bits!` for the markup).

/// One bit of a table the C header shows: its name, value and documentation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct BitSpec {
    /// The constant's name, e.g. `ACCEL_USED`.
    pub name: &'static str,
    pub value: u32,
    /// The doc comment's lines, each ending in a newline.
    pub doc: &'static str,
}

/// The one place a table of bits is defined. From one entry per bit (its doc comment,
/// name and value) it makes the documented `pub const NAME: u32` and `TABLE`, the
/// [`BitSpec`]s in order, from which the C constants are rendered (`src/ffi/bits.rs`).
///
/// The text is written for both languages: `` [`NAME`] `` (a link to a bit of the same
/// table) becomes that bit's C constant, and a parameter name in backticks (`gap_dt`) its
/// `ORIENT_PARAM_*` constant.
macro_rules! bits {
    ($( $(#[doc = $doc:literal])+ $name:ident = $value:literal; )*) => {
        $(
            $(#[doc = $doc])+
            pub const $name: u32 = $value;
        )*

        /// Every bit of this table, in order, with its documentation.
        #[cfg_attr(not(test), allow(dead_code))]
        pub(crate) const TABLE: &[$crate::filters::flags::BitSpec] = &[
            $(
                $crate::filters::flags::BitSpec {
                    name: stringify!($name),
                    value: $value,
                    doc: concat!($($doc, "\n"),+),
                },
            )*
        ];
    };
}
pub(crate) use bits;

bits! {
    /// The filter has an orientation. Clear while it waits for its first accelerometer
    /// sample (the default initialisation, from the accelerometer and magnetometer), and
    /// through the start-up
    /// period of the complementary and GMVDK kinds, `init_duration` seconds of samples
    /// with an accelerometer reading: their readings are averaged into the initial
    /// orientation, and each such sample sets [`ACCEL_USED`] and, for the magnetometer,
    /// [`MAG_USED`] or [`MAG_REJECTED`] as the period will use it; the dt = 0 samples of
    /// `same_instant` are samples of the period too.
    INITIALIZED = 1;
    /// The last accepted update used the accelerometer.
    ACCEL_USED = 2;
    /// The last accepted update used the magnetometer.
    MAG_USED = 4;
    /// The last accepted update followed a gap (dt above `gap_dt`). Nothing was
    /// integrated over the gap, whose motion is unknown: the update re-acquired the
    /// orientation ([`REACQUIRED`]) or, on a sample without an accelerometer reading,
    /// held it ([`REACQUIRE_PENDING`]). During the start-up period of the complementary
    /// and GMVDK kinds the period started over with the sample instead (not at a gap
    /// right after a gap: where every sample is one, it goes on, and its stillness test
    /// alone starts it over).
    GAP = 8;
    /// The last accepted update re-acquired the orientation (after a gap, a gyroscope
    /// saturation or the rest watch, see [`REACQUIRE_PENDING`]): inclination from its
    /// accelerometer reading, heading from its magnetometer reading when it has one
    /// (every kind but the robust one, whose magnetic disturbance test may refuse the
    /// reading, and the complementary one, which uses it only with `align_heading`), else
    /// the heading held before. The kind's low-passes and detectors start over; its bias
    /// estimate is kept, but after the rest watch the still sample's gyroscope reading
    /// becomes the bias of every kind that learns one or still subtracts one (the
    /// complementary filter's rest reference ω_b0 too).
    REACQUIRED = 16;
    /// The next sample with an accelerometer reading re-acquires the orientation
    /// ([`REACQUIRED`]); until then it is integrated from the gyroscope. Set when a gap
    /// ends on a sample without an accelerometer reading (the orientation is held over
    /// the gap), after gyroscope saturation, and by the rest watch: when the sensor lies
    /// still (gyroscope below 3 °/s, accelerometer norm within 5 % of the configured
    /// gravity) and the estimate's vertical has been more than 10° from the
    /// accelerometer's, or the kind's bias more than 6 °/s from the gyroscope's reading,
    /// for 5 s net of the time it was not (looked at every 128th sample, at least four
    /// looks; a look at a moving sensor starts the count over). An estimate can rest
    /// there at a stationary point of its kind's correction (Madgwick's and Mahony's
    /// magnetometer terms near a 180° heading error, the EKF's gravity update near an
    /// upside-down estimate), or spin on a wrong bias that its kind then cannot learn
    /// (GMVDK distrusts the accelerometer while the de-biased rate is large, the
    /// complementary filter's rest test compares with its start-up bias).
    REACQUIRE_PENDING = 32;
    /// The last accepted sample had an accelerometer reading that the update did not use
    /// (the kind's own test turned it down, e.g. the robust kind's and the EKF's gating of
    /// linear acceleration, GMVDK's trust, McGinnis' rest gate).
    ACCEL_REJECTED = 64;
    /// The last accepted sample had a magnetometer reading that the update did not use
    /// (the kind has no heading correction, the field defines no north, or the kind
    /// turned it down).
    MAG_REJECTED = 128;
    /// The kind counts the magnetic field as disturbed now (the robust kind: the last
    /// reading failed its norm and dip tests, hard iron compensated). Read from the
    /// state, not stored.
    MAG_DISTURBED = 256;
    /// The kind counts the sensor as resting now (McGinnis' and the robust kind's rest
    /// detection; the EKF, Madgwick and Mahony with their rest options on,
    /// `rest_rate_std` and `rest_bias_tau`; GMVDK never sets it). Read from the state,
    /// not stored.
    REST = 512;
    /// The last update had a reading at or beyond its configured range and used it
    /// clipped (`saturation_recovery` = 1): a gyroscope reading clipped just under the
    /// range, an accelerometer reading left out. After gyroscope saturation
    /// [`REACQUIRE_PENDING`] is set too: the next unsaturated sample with an
    /// accelerometer reading re-acquires the orientation ([`REACQUIRED`]).
    SATURATED = 1024;
    /// The last sample had dt = 0 and was taken as the same instant as the next sample
    /// with dt > 0 (`same_instant` = 1): nothing was integrated; its gyroscope reading is
    /// averaged into that sample's step.
    SAME_INSTANT = 2048;
}

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
pub const ALL: u32 = {
    let mut all = 0;
    let mut i = 0;
    while i < TABLE.len() {
        all |= TABLE[i].value;
        i += 1;
    }
    all
};
