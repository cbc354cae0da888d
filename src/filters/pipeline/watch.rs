//! The rest watch: every kind's way back from an estimate that has settled on a wrong
//! inclination while the sensor lies still.
//!
//! A kind's correction can have a stationary point away from the truth. Madgwick's and
//! Mahony's magnetometer terms have one near a heading error of 180°: there the field's
//! gradient tilts the estimate against the accelerometer's, and the two balance with the
//! inclination some 17° off, for minutes. The EKF's gravity update has one near an
//! inclination error of 180°, where the innovation is parallel to the prediction. Nothing
//! local to a paper's equations leaves such a point quickly, so the lifecycle watches for
//! what every kind at rest must agree with: the accelerometer's vertical.
//!
//! After every [`WATCH_EVERY`] accepted samples, the watch looks at the next one. The
//! sensor counts as lying still when the gyroscope reads less than [`STILL_RATE`] and the
//! accelerometer's norm is the configured gravity's within [`STILL_GRAVITY`]. While it
//! lies still, the watch adds up the time of every look at which the estimate's vertical
//! is more than [`OFF_ANGLE`] from the accelerometer's, or the kind's bias estimate is
//! more than [`SPIN_RATE`] from the gyroscope's reading, and takes off the time of every
//! look at which it is closer (an estimate that spins on a wrong bias passes the vertical
//! now and then); a look at a sensor that does not lie still starts it over. When the sum
//! reaches [`OFF_SECONDS`] the watch leaves a re-acquisition pending, which the next sample
//! takes (`flags::REACQUIRE_PENDING`, `flags::REACQUIRED`): inclination from the
//! accelerometer, heading from the magnetometer where the kind takes it.
//!
//! What the watch re-acquires is where the kind's own correction would have gone at rest,
//! had it no stationary point in the way: every kind's rest attitude is the
//! accelerometer's vertical (and, where it takes it, the field's heading). A steady
//! acceleration that passes for gravity over the whole period (a vehicle in a long
//! curve, turning slower than [`STILL_RATE`]) moves a kind's estimate there too, only
//! more slowly. A correct estimate at rest is within a degree or two of the
//! accelerometer's vertical, but one whose gyroscope bias is still being learned can rest
//! further off: a watch at 2° fired on the robust kind started with a 0.05 rad/s bias
//! (tests/offline.rs) and restarted its detectors. [`OFF_ANGLE`] leaves such a kind's own
//! convergence alone.

use crate::filters::state::Codec;
use crate::math::{Quat, Vec3};

/// How many accepted samples lie between two looks: the cost of the watch is a count per
/// sample and one look per [`WATCH_EVERY`] samples (1.28 s at 100 Hz). A look takes the
/// policies' path, some 500 instructions in all: at 32 it cost the usual update 17 of its
/// 281 (Madgwick IMU, callgrind), at 128 four.
pub(crate) const WATCH_EVERY: u16 = 128;

/// The most time one look adds: a quarter of [`OFF_SECONDS`], so that at any rate (at 25
/// Hz a look comes every 5.12 s) at least four looks must find the estimate off.
const MOST_PER_LOOK: f32 = (OFF_SECONDS / 4.0) as f32;

/// The fastest gyroscope reading of a sensor that lies still (rad/s): 3 °/s, above the
/// zero-rate offset of a calibrated MEMS gyroscope, far below any hand motion.
pub(crate) const STILL_RATE: f64 = 0.052_359_877_559_829_89;

/// How far a still accelerometer's norm may be from the configured gravity, as a share
/// of it.
pub(crate) const STILL_GRAVITY: f64 = 0.05;

/// The angle between the estimated and the measured vertical beyond which a look counts
/// as off: 10°.
pub(crate) const OFF_ANGLE: f64 = 0.174_532_925_199_432_95;

/// The de-biased rate beyond which a kind's estimate of a sensor that lies still counts
/// as off whatever its vertical (rad/s): 6 °/s, twice [`STILL_RATE`]. A gyroscope that
/// reads under [`STILL_RATE`] then has a bias estimate more than 3 °/s from its reading:
/// the estimate turns where the sensor does not (about the vertical too, where the
/// accelerometer cannot see it), and a kind whose own rest test compares with that bias
/// (the complementary filter) or whose trust in the accelerometer falls with that rate
/// (GMVDK) never learns it back.
pub(crate) const SPIN_RATE: f64 = 2.0 * STILL_RATE;

/// How long, net, the estimate must be off while the sensor lies still (s).
pub(crate) const OFF_SECONDS: f64 = 5.0;

/// The watch's state: samples to the next look, and the time the estimate has been off
/// at rest, less the time it has been on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Watch {
    countdown: u16,
    /// The watch left the pending re-acquisition (see [`Watch::still`]).
    due: bool,
    off: f32,
}

impl Default for Watch {
    fn default() -> Watch {
        Watch { countdown: WATCH_EVERY, due: false, off: 0.0 }
    }
}

impl Watch {
    /// Counts an accepted step; true when the count runs out: the next sample is the one
    /// to look at. (That sample's step counts on past 0; the look then starts the count
    /// over, so that one sample in [`WATCH_EVERY`] is looked at.)
    #[inline(always)]
    pub(crate) fn tick(&mut self) -> bool {
        self.countdown = self.countdown.wrapping_sub(1);
        self.countdown == 0
    }

    /// The count ran out: the next sample is looked at.
    pub(crate) fn looks_next(&self) -> bool {
        self.countdown == 0
    }

    /// The look at a sample (`dt`, its gyroscope and accelerometer readings) and the
    /// estimate `q` after it (sensor to earth, in the frame whose vertical is `up`) with
    /// the kind's gyroscope `bias` (NaN where it has none), with the configured
    /// `gravity`: true when a re-acquisition is due.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn look(
        &mut self,
        dt: f64,
        gyro: Vec3,
        accel: Option<Vec3>,
        q: Quat,
        bias: Vec3,
        up: Vec3,
        gravity: f64,
    ) -> bool {
        // This sample's own step counted past 0: the next look is WATCH_EVERY samples on.
        self.countdown = WATCH_EVERY - 1;
        let (still, off) = accel.map_or((false, false), |a| {
            let n = a.norm();
            let still = gyro.norm_squared() < STILL_RATE * STILL_RATE
                && (n - gravity).abs() <= STILL_GRAVITY * gravity;
            let spins = (gyro - bias).norm_squared() > SPIN_RATE * SPIN_RATE;
            (still, still && (spins || a.dot(q.rotate_inverse(up)) < OFF_ANGLE.cos() * n))
        });
        let period = ((dt * f64::from(WATCH_EVERY)) as f32).min(MOST_PER_LOOK);
        if !still {
            self.off = 0.0;
            return false;
        }
        if !off {
            // Counted down, not started over: an estimate that spins while the sensor lies
            // still (on a wrong bias) passes the vertical now and then, and is off at most
            // looks.
            self.off = (self.off - period).max(0.0);
            return false;
        }
        self.off += period;
        if f64::from(self.off) < OFF_SECONDS {
            return false;
        }
        self.off = 0.0;
        self.due = true;
        true
    }

    /// At the re-acquisition: the gyroscope reading `gyro` when the watch asked for it
    /// and the sensor still lies still, the bias of a sensor at rest. Every kind that
    /// learns a bias takes it: one wound up while the estimate was off would carry the
    /// error on, and a bias far from the reading is what made a spinning estimate off.
    pub(crate) fn still(&self, gyro: Vec3) -> Option<Vec3> {
        (self.due && gyro.norm_squared() < STILL_RATE * STILL_RATE).then_some(gyro)
    }

    /// Starts over (a reset, a re-acquisition, a new orientation).
    pub(crate) fn restart(&mut self) {
        *self = Watch::default();
    }

    pub(crate) fn codec(&mut self, c: &mut dyn Codec) {
        let mut countdown = u32::from(self.countdown);
        c.u32(&mut countdown);
        self.countdown = countdown.min(u32::from(u16::MAX)) as u16;
        c.bool(&mut self.due);
        let mut off = f64::from(self.off);
        c.f64(&mut off);
        self.off = if off.is_finite() { off.clamp(0.0, OFF_SECONDS) as f32 } else { 0.0 };
    }
}
