//! The static start-up period of the complementary filter and GMVDK: running sums of the
//! readings over the period, and their means.

use super::state::Codec;
use crate::math::Vec3;

#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct StartupMeans {
    time: f64,
    n: u32,
    gyro: Vec3,
    accel: Vec3,
    accel_norm: f64,
    mag: Vec3,
    n_mag: u32,
}

impl StartupMeans {
    /// Adds one sample; true once the sums cover `duration` seconds.
    pub fn add(&mut self, dt: f64, gyro: Vec3, accel: Vec3, mag: Option<Vec3>, duration: f64) -> bool {
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

    pub fn gyro(&self) -> Vec3 {
        self.gyro * (1.0 / self.n as f64)
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
