//! Rigs of sensors on segments with known mountings (issue 20): each sensor's reading
//! is simulated from its segment's motion, with the mounting between them.
#![allow(dead_code)]

use super::sim::{simulate, Moment, Noise, Run};
use orient::{Quat, Vec3};

/// One segment of a simulated rig.
pub struct Segment {
    /// Its orientation in the reference posture (segment to posture frame).
    pub reference: Quat,
    /// Sensor to segment: `v_segment = mounting v_sensor`.
    pub mounting: Quat,
    /// The sensor's samples and true orientations (sensor to earth, ENU).
    pub run: Run,
}

impl Segment {
    /// The segment's true orientation in the posture frame at sample `i`, for a subject
    /// facing `heading` (the posture frame turned by that yaw from ENU).
    pub fn truth(&self, i: usize, heading: f64) -> Quat {
        let g = Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), heading);
        (g.conj() * self.run.truth[i] * self.mounting.conj()).normalized()
    }
}

/// A random unit quaternion (uniform enough for tests).
pub fn random_rotation(rng: &mut Noise) -> Quat {
    loop {
        let q = Quat::new(rng.next(), rng.next(), rng.next(), rng.next());
        if q.norm_squared() > 0.05 && q.norm_squared() <= 1.0 {
            return q.normalized();
        }
    }
}

/// A rig of `references.len()` segments: the subject faces `heading` and holds the
/// reference posture for `still` seconds, then each segment turns with its own smooth
/// body rate (up to about 0.7 rad/s) for `moving` seconds. 100 Hz, with small sensor
/// noise.
pub fn rig(references: &[Quat], mountings: &[Quat], heading: f64, still: f64, moving: f64) -> Vec<Segment> {
    let g = Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), heading);
    references
        .iter()
        .zip(mountings)
        .enumerate()
        .map(|(k, (r, m))| {
            let start = (g * *r * *m).normalized();
            let phase = k as f64 * 0.7;
            let run = simulate(start, still + moving, 100.0, (0.0005, 0.005, 0.02), |t| {
                let omega_segment = if t <= still {
                    Vec3::ZERO
                } else {
                    let u = t - still;
                    Vec3::new(
                        0.5 * (1.3 * u + phase).sin(),
                        0.3 * (0.9 * u + 2.0 * phase).cos(),
                        0.6 * (0.5 * u + phase).sin(),
                    )
                };
                // The sensor turns with its segment: its body rate is the segment's in
                // the sensor's axes.
                Moment { omega: m.rotate_inverse(omega_segment), ..Moment::default() }
            });
            Segment { reference: *r, mounting: *m, run }
        })
        .collect()
}

/// A soft-iron matrix (symmetric, as a soft-iron distortion is) and a hard-iron offset
/// (µT) for the magnetometer checks.
pub const SOFT_IRON: [[f64; 3]; 3] = [[1.12, 0.06, -0.04], [0.06, 0.88, 0.03], [-0.04, 0.03, 1.03]];
pub const HARD_IRON: Vec3 = Vec3::new(15.0, -8.0, 30.0);

/// `SOFT_IRON v + HARD_IRON`: what a distorted magnetometer reads for the field `v`.
pub fn distort(v: Vec3) -> Vec3 {
    let m = SOFT_IRON;
    Vec3::new(
        m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
        m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
        m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z,
    ) + HARD_IRON
}

/// `seconds` of a sensor tumbling through every orientation at 50 Hz (turning about
/// all three axes at incommensurate rates), with small noise.
pub fn tumble(seconds: f64) -> Run {
    simulate(Quat::IDENTITY, seconds, 50.0, (0.001, 0.02, 0.2), |t| Moment {
        omega: Vec3::new(0.9 * (0.31 * t).sin(), 0.7 * (0.23 * t).cos(), 0.8 + 0.3 * (0.17 * t).sin()),
        ..Moment::default()
    })
}
