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
