//! The static start-up period of the complementary filter and GMVDK: running sums of the
//! readings over the period, and their means. Both papers take the initial bias and
//! attitude from a still period; a period that was not still would give them a wrong
//! bias and reference for good (McGinnis' rest test compares with them), so a sample
//! that is not still starts the period over from that sample. Not still is:
//! - a gyroscope reading that leaves the period's mean rate by more than the kind's
//!   threshold, or one faster than [`MAX_STILL_RATE`] (no gyroscope's offset is that
//!   large: a steady turn would otherwise pass for a still sensor with a large bias);
//! - an accelerometer reading whose norm is not the configured gravity's, within
//!   [`GRAVITY_STILL`] (the period's mean norm becomes the kinds' rest reference);
//! - an accelerometer reading that leaves the period's mean *vector* by more than the
//!   kind's threshold (a turn about any axis but the vertical turns it; its norm alone
//!   does not change);
//! - a magnetometer reading that leaves the period's mean by more than [`MAG_STILL`]
//!   of its norm (a turn about the vertical turns it).
//!
//! A sensor that never keeps still is not waited for forever: once [`PATIENCE`] periods
//! have passed, the period in progress is finished whatever the motion, with a zero bias
//! (the mean rate of a motion is no bias).

/// How many start-up durations to wait for a still period before starting without one.
pub(crate) const PATIENCE: f64 = 5.0;

/// The fastest gyroscope reading a still sensor gives (rad/s): 20 °/s, the worst-case
/// zero-rate offset of common MEMS gyroscopes (InvenSense MPU-6050 datasheet, ±20 °/s
/// initial tolerance).
pub(crate) const MAX_STILL_RATE: f64 = 0.349_065_850_398_865_9;

/// How far a still accelerometer's norm may be from the configured gravity, as a share
/// of it: 0.1, three times the ±3 % sensitivity tolerance of common MEMS accelerometers
/// (InvenSense MPU-6050 datasheet), so that a mis-scaled but still sensor starts, while
/// a constant reading that is no gravity (a glitch held over the period, a sensor
/// accelerating steadily) does not become the rest reference.
pub(crate) const GRAVITY_STILL: f64 = 0.1;

/// A stationary accelerometer norm `g0` after the configured gravity became `gravity`:
/// kept when it is that gravity's within [`GRAVITY_STILL`], else the gravity itself (a
/// norm the start-up would not take now); 0 (not known yet) stays 0.
pub(crate) fn stationary_norm(g0: f64, gravity: f64) -> f64 {
    if g0 == 0.0 || (g0 - gravity).abs() <= GRAVITY_STILL * gravity {
        g0
    } else {
        gravity
    }
}

/// How far a still sensor's magnetometer reading may leave the period's mean, as a share
/// of the mean's norm: 0.1, a turn of about 6° about the vertical, or a disturbance of a
/// tenth of the field.
pub(crate) const MAG_STILL: f64 = 0.1;

use crate::filters::state::Codec;
use crate::math::Vec3;

#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct StartupMeans {
    /// Time since the first start-up sample, over restarts (s).
    elapsed: f64,
    /// A sample that was not still came after the patience ran out.
    moved: bool,
    time: f64,
    n: u32,
    gyro: Vec3,
    accel: Vec3,
    accel_norm: f64,
    mag: Vec3,
    n_mag: u32,
}

/// How far a start-up sample may lie from the period's mean and still count as still.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Stillness {
    /// |ω − mean ω| (rad/s).
    pub gyro: f64,
    /// |a − mean a| (m/s²).
    pub accel: f64,
    /// The configured gravity (m/s²): a still accelerometer reads its magnitude, within
    /// [`GRAVITY_STILL`] of it.
    pub gravity: f64,
}

impl Stillness {
    /// The readings lie within the thresholds of the period's means.
    fn holds(&self, s: &StartupMeans, gyro: Vec3, accel: Vec3) -> bool {
        (gyro - s.gyro()).norm() <= self.gyro && (accel - s.accel()).norm() <= self.accel
    }

    /// The accelerometer reads gravity's magnitude, as a still one does.
    fn reads_gravity(&self, accel: Vec3) -> bool {
        (accel.norm() - self.gravity).abs() <= GRAVITY_STILL * self.gravity
    }
}

impl StartupMeans {
    /// The magnetometer reading, when there is one and the period has a mean, lies within
    /// [`MAG_STILL`] of that mean.
    fn mag_still(&self, mag: Option<Vec3>) -> bool {
        match (mag, self.mag()) {
            (Some(m), Some(mean)) => (m - mean).norm() <= MAG_STILL * mean.norm(),
            _ => true,
        }
    }

    /// Adds one sample; true once the sums cover `duration` seconds. A sample that is not
    /// still against the period so far starts the period over.
    pub fn add(
        &mut self,
        dt: f64,
        gyro: Vec3,
        accel: Vec3,
        mag: Option<Vec3>,
        duration: f64,
        still: Stillness,
    ) -> bool {
        let alone_not_still = gyro.norm() > MAX_STILL_RATE || !still.reads_gravity(accel);
        if alone_not_still || self.n > 0 && (!still.holds(self, gyro, accel) || !self.mag_still(mag)) {
            if self.elapsed < PATIENCE * duration {
                *self = StartupMeans { elapsed: self.elapsed, ..StartupMeans::default() };
            } else {
                self.moved = true;
            }
        }
        self.elapsed += dt;
        self.time += dt;
        self.n += 1;
        self.gyro = self.gyro + gyro;
        self.accel = self.accel + accel;
        self.accel_norm += accel.norm();
        if let Some(m) = mag {
            self.mag = self.mag + m;
            self.n_mag += 1;
        }
        self.time + 1e-12 >= duration
    }

    /// Values `add` could leave: sums of bounded readings, counts that match.
    pub fn valid(&self) -> bool {
        use crate::filters::pipeline::sample::MAX_ACCEL;
        use crate::filters::pipeline::sample::MAX_GYRO;
        use crate::filters::pipeline::sample::MAX_MAG;
        use crate::filters::state::holds;
        let n = f64::from(self.n).max(1.0);
        self.time >= 0.0
            && self.elapsed >= self.time
            && self.n_mag <= self.n
            && self.gyro.max_abs() <= MAX_GYRO * n
            && self.accel.max_abs() <= MAX_ACCEL * n
            && holds::within(self.accel_norm, 0.0, 2.0 * MAX_ACCEL * n)
            && self.mag.max_abs() <= MAX_MAG * n
    }

    /// A period [`StartupMeans::valid`] turns down (for a snapshot that holds an
    /// impossible one).
    pub fn invalid() -> StartupMeans {
        StartupMeans { time: -1.0, ..StartupMeans::default() }
    }

    /// The period has taken a sample (the kind is in its start-up stage, not waiting
    /// for a first sample).
    pub fn begun(&self) -> bool {
        self.n > 0
    }

    pub fn gyro(&self) -> Vec3 {
        self.gyro * (1.0 / self.n as f64)
    }

    /// True when the period ended without keeping still (the patience ran out).
    pub fn moved(&self) -> bool {
        self.moved
    }

    /// The initial bias: the mean rate of a still period, zero after motion.
    pub fn bias(&self) -> Vec3 {
        if self.moved {
            Vec3::ZERO
        } else {
            self.gyro()
        }
    }

    pub fn accel(&self) -> Vec3 {
        self.accel * (1.0 / self.n as f64)
    }

    /// The mean accelerometer norm (not the norm of the mean).
    pub fn accel_norm(&self) -> f64 {
        self.accel_norm / self.n as f64
    }

    /// The mean magnetometer reading, when the period had any.
    pub fn mag(&self) -> Option<Vec3> {
        (self.n_mag > 0).then(|| self.mag * (1.0 / self.n_mag as f64))
    }

    /// Encodes an optional period (a snapshot taken during start-up or after it).
    pub fn codec(s: &mut Option<StartupMeans>, c: &mut dyn Codec) {
        let mut present = s.is_some();
        c.bool(&mut present);
        let mut v = s.clone().unwrap_or_default();
        c.f64(&mut v.elapsed);
        c.bool(&mut v.moved);
        c.f64(&mut v.time);
        c.u32(&mut v.n);
        c.vec3(&mut v.gyro);
        c.vec3(&mut v.accel);
        c.f64(&mut v.accel_norm);
        c.vec3(&mut v.mag);
        c.u32(&mut v.n_mag);
        *s = present.then_some(v);
    }
}
