//! A small IMU/MARG simulator for tests with known truth: integrate a body angular
//! velocity exactly, and write what ideal sensors (plus bias, noise and disturbances)
//! would read, in ENU.
#![allow(dead_code)]

use orient::filters::complementary::rotation_of;
use orient::{Quat, Sample, Vec3};

/// Earth's field in ENU, µT: 20 north, 40 down (dip 63°).
pub const FIELD: Vec3 = Vec3::new(0.0, 20.0, -40.0);
pub const G: f64 = 9.81;

/// Deterministic uniform noise in [-1, 1).
pub struct Noise(pub u64);

impl Noise {
    pub fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
    pub fn vec(&mut self, scale: f64) -> Vec3 {
        Vec3::new(self.next() * scale, self.next() * scale, self.next() * scale)
    }
}

/// What happens at time t.
pub struct Moment {
    /// Body angular velocity, rad/s.
    pub omega: Vec3,
    /// Linear acceleration in ENU, m/s².
    pub linear: Vec3,
    /// Magnetic field in ENU, µT (FIELD unless disturbed).
    pub field: Vec3,
    /// Gyroscope bias, rad/s.
    pub bias: Vec3,
}

impl Default for Moment {
    fn default() -> Self {
        Moment { omega: Vec3::ZERO, linear: Vec3::ZERO, field: FIELD, bias: Vec3::ZERO }
    }
}

pub struct Run {
    pub samples: Vec<Sample>,
    pub truth: Vec<Quat>,
    pub t: Vec<f64>,
}

/// Simulates `seconds` at `rate` Hz from `start`, with white noise of the given scales
/// (uniform, so the standard deviation is scale/√3).
pub fn simulate(
    start: Quat,
    seconds: f64,
    rate: f64,
    noise: (f64, f64, f64),
    mut at: impl FnMut(f64) -> Moment,
) -> Run {
    let dt = 1.0 / rate;
    let n = (seconds * rate).round() as usize;
    let mut q = start;
    let mut rng = Noise(0x9e37_79b9_7f4a_7c15);
    let mut run =
        Run { samples: Vec::with_capacity(n), truth: Vec::with_capacity(n), t: Vec::with_capacity(n) };
    for i in 0..n {
        let t = (i + 1) as f64 * dt;
        let m = at(t);
        q = (q * rotation_of(m.omega, dt)).normalized();
        let accel = q.rotate_inverse(Vec3::new(0.0, 0.0, G) + m.linear) + rng.vec(noise.1);
        let mag = q.rotate_inverse(m.field) + rng.vec(noise.2);
        run.samples.push(Sample {
            dt,
            gyro: Some(m.omega + m.bias + rng.vec(noise.0)),
            accel: Some(accel),
            mag: Some(mag),
        });
        run.truth.push(q);
        run.t.push(t);
    }
    run
}

/// The rate that takes `from` to `to` (both sensor-to-earth) in `seconds` at constant
/// body angular velocity.
pub fn rate_between(from: Quat, to: Quat, seconds: f64) -> Vec3 {
    let d = from.conj() * to; // body-frame rotation
    let d = if d.w < 0.0 { d.scale(-1.0) } else { d };
    let v = d.vector();
    let s = v.norm();
    if s < 1e-15 {
        return Vec3::ZERO;
    }
    let angle = 2.0 * s.atan2(d.w);
    v * (angle / s / seconds)
}

/// Angle of the tilt part of the error between two orientations (ENU), radians.
pub fn inclination_error(est: Quat, truth: Quat) -> f64 {
    let up = Vec3::new(0.0, 0.0, 1.0);
    let a = est.rotate_inverse(up);
    let b = truth.rotate_inverse(up);
    a.dot(b).clamp(-1.0, 1.0).acos()
}

/// A sample as the C ABI's OrientSample; absent sensors have their flag cleared.
pub fn c_sample(s: &Sample) -> orient::ffi::OrientSample {
    use orient::ffi::*;
    let v = |v: Option<Vec3>| v.map_or(OrientVec3::default(), |v| OrientVec3 { x: v.x, y: v.y, z: v.z });
    let flag = |present: bool, bit: u32| if present { bit } else { 0 };
    OrientSample {
        dt: s.dt,
        gyro: v(s.gyro),
        accel: v(s.accel),
        mag: v(s.mag),
        flags: flag(s.gyro.is_some(), ORIENT_SAMPLE_GYRO)
            | flag(s.accel.is_some(), ORIENT_SAMPLE_ACCEL)
            | flag(s.mag.is_some(), ORIENT_SAMPLE_MAG),
        reserved: 0,
    }
}
