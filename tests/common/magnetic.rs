//! Simulated protocols with exact truth for the recommended kind's magnetometer and bias
//! mechanisms (issue 19): a magnet attached to the sensor (a hard-iron step), a start
//! inside a magnet's field, a gyro bias drifting past 2 °/s, and hand-held motion.
//! Built on `sim::simulate`; every protocol is deterministic.
#![allow(dead_code)]

use super::sim::{simulate, Moment, Run, FIELD};
use orient::{Quat, Vec3};

/// Noise scales (uniform, see `simulate`) of a consumer MEMS IMU: gyro rad/s, accel
/// m/s², mag µT.
pub const NOISE: (f64, f64, f64) = (0.005, 0.05, 0.5);

/// Hand-held motion: smooth turns about every axis (up to about 1.5 rad/s) and a
/// zero-mean linear acceleration of up to 2 m/s², after `rest` seconds of rest.
pub fn hand_held_moment(t: f64, rest: f64) -> Moment {
    if t < rest {
        return Moment::default();
    }
    let u = t - rest;
    Moment {
        omega: Vec3::new(
            0.9 * (0.8 * u).sin() + 0.3 * (2.3 * u).sin(),
            0.7 * (0.6 * u + 1.0).cos() + 0.2 * (1.9 * u).cos(),
            0.8 * (0.45 * u).sin() + 0.25 * (2.9 * u + 0.5).sin(),
        ),
        linear: Vec3::new(1.5 * (1.7 * u).sin(), 1.2 * (2.1 * u + 0.3).cos(), 2.0 * (1.3 * u).sin()),
        ..Default::default()
    }
}

/// 60 s hand-held at `rate` Hz after 5 s of rest.
pub fn hand_held(rate: f64) -> Run {
    simulate(Quat::IDENTITY, 65.0, rate, NOISE, |t| hand_held_moment(t, 5.0))
}

/// Hand-held at 100 Hz; from 20 s a magnet fixed to the sensor adds `offset` (µT, sensor
/// frame) to every magnetometer reading, until the end at 120 s.
pub fn attached_magnet(offset: Vec3) -> Run {
    let mut run = simulate(Quat::IDENTITY, 120.0, 100.0, NOISE, |t| hand_held_moment(t, 5.0));
    for (s, t) in run.samples.iter_mut().zip(&run.t) {
        if *t >= 20.0 {
            s.mag = s.mag.map(|m| m + offset);
        }
    }
    run
}

/// The field near a magnet in the room where the sensor starts: 69.6 µT (the earth's is
/// 44.7), its horizontal part 45° from north.
pub const MAGNET_FIELD: Vec3 = Vec3::new(25.0, 25.0, -60.0);

/// At rest for 30 s at `MAGNET_FIELD`, then carried away (the earth's field from then
/// on) and moved by hand for 60 s, at 100 Hz.
pub fn start_in_disturbance() -> Run {
    simulate(Quat::IDENTITY, 90.0, 100.0, NOISE, |t| Moment {
        field: if t < 30.0 { MAGNET_FIELD } else { FIELD },
        ..hand_held_moment(t, 30.0)
    })
}

/// The bias of [`drifting_bias`] at time t: from 0.5 °/s per axis, growing by 0.01 °/s
/// each second, to 3.5 °/s per axis (6 °/s in norm) at 300 s.
pub fn drift(t: f64) -> Vec3 {
    let d = (0.5 + 0.01 * t).to_radians();
    Vec3::new(d, -d, d)
}

/// 300 s at 100 Hz: 10 s of rest, then 20 s of hand-held motion and 10 s of rest in
/// turn, with the gyro bias of [`drift`].
pub fn drifting_bias() -> Run {
    simulate(Quat::IDENTITY, 300.0, 100.0, NOISE, |t| {
        let phase = t % 30.0;
        let m = if phase < 10.0 { Moment::default() } else { hand_held_moment(t, 0.0) };
        Moment { bias: drift(t), ..m }
    })
}
