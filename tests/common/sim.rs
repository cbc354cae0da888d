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

// ---- The seed papers' protocols (tests/paper_claims.rs) ----------------------------------

/// A sequence of poses: from `start`, each entry turns at constant body rate to its
/// orientation in `move_s` seconds, then holds it for `hold_s` seconds. Returns the body
/// rate at time t (the first `lead` seconds still).
pub struct Poses {
    /// (start time, end time, body rate) of each move.
    moves: Vec<(f64, f64, Vec3)>,
    pub end: f64,
}

impl Poses {
    pub fn new(start: Quat, lead: f64, poses: &[(Quat, f64, f64)]) -> Poses {
        let (mut t, mut from, mut moves) = (lead, start, Vec::new());
        for &(to, move_s, hold_s) in poses {
            moves.push((t, t + move_s, rate_between(from, to, move_s)));
            t += move_s + hold_s;
            from = to;
        }
        Poses { moves, end: t }
    }

    /// Body rate at t, and whether a move is under way.
    pub fn rate(&self, t: f64) -> (Vec3, bool) {
        // Samples integrate the rate over (t - dt, t]: a move is [start, end) shifted by
        // one sample, which the caller's rate makes negligible.
        self.moves
            .iter()
            .find(|(a, b, _)| t > *a && t <= *b)
            .map_or((Vec3::ZERO, false), |(_, _, w)| (*w, true))
    }
}

/// Uniform noise scale for a white-noise density (unit/√Hz) sampled at `rate`: the
/// standard deviation is density·√(rate/2), and a uniform scale s has deviation s/√3.
pub fn scale_of_density(density: f64, rate: f64) -> f64 {
    density * (rate / 2.0).sqrt() * 3f64.sqrt()
}

/// Madgwick 2010 (section VI): an xsens MTx turned by hand about each of its axes in
/// turn, then about all of them together; the paper logs at 512 Hz and reports static
/// and dynamic RMS errors (Table I). Here: 10 s still, then for each axis 10 s of
/// ±60° sinusoidal turns at 0.4 Hz, then 30 s of turns about all axes; the hand's
/// linear acceleration (about 1 m/s²) with the turns; MTx noise densities (gyro
/// 0.05°/s/√Hz, accelerometer 0.002 m/s²/√Hz, magnetometer 0.5 mGauss/√Hz = 0.05 µT/√Hz)
/// and a residual gyro bias of 0.2°/s after the MTx's calibration.
pub fn hand_held(rate: f64) -> Run {
    let noise = (
        scale_of_density(0.05f64.to_radians(), rate),
        scale_of_density(0.002, rate),
        scale_of_density(0.05, rate),
    );
    let bias = Vec3::new(0.2, -0.15, 0.1) * 0.2f64.to_radians();
    let w = 2.0 * core::f64::consts::PI * 0.4;
    let amp = 60f64.to_radians() * w; // peak rate of ±60° at 0.4 Hz
    simulate(Quat::from_axis_angle(Vec3::new(0.2, 0.1, 1.0), 0.5), 70.0, rate, noise, move |t| {
        let omega = match t {
            t if t < 10.0 => Vec3::ZERO,
            t if t < 20.0 => Vec3::new(amp * (w * (t - 10.0)).cos(), 0.0, 0.0),
            t if t < 30.0 => Vec3::new(0.0, amp * (w * (t - 20.0)).cos(), 0.0),
            t if t < 40.0 => Vec3::new(0.0, 0.0, amp * (w * (t - 30.0)).cos()),
            t => Vec3::new(
                0.6 * amp * (w * (t - 40.0)).cos(),
                0.5 * amp * (1.3 * w * (t - 40.0)).cos(),
                0.4 * amp * (0.7 * w * (t - 40.0)).cos(),
            ),
        };
        let linear = if t < 10.0 {
            Vec3::ZERO
        } else {
            Vec3::new((w * t).sin(), (1.3 * w * t).cos(), 0.5 * (0.7 * w * t).sin())
        };
        Moment { omega, linear, bias, ..Moment::default() }
    })
}

/// YEI 3-Space noise densities (McGinnis 2014, section 2): gyro 0.03°/s/√Hz,
/// accelerometer 650 µg/√Hz; magnetometer as the MTx's.
fn yei_noise(rate: f64) -> (f64, f64, f64) {
    (
        scale_of_density(0.03f64.to_radians(), rate),
        scale_of_density(650e-6 * G, rate),
        scale_of_density(0.05, rate),
    )
}

/// McGinnis 2014: the up-down manoeuvre, torso IMU. Five get-down-get-up cycles from
/// standing to lying prone and back, pausing in each position; 100 Hz (the MOCAP rate;
/// the paper does not give the IMU's). The torso pitches 90° forward in 1.2 s with a
/// linear acceleration of up to 3 m/s² along the way, pauses 2 s prone, rises in 1.2 s,
/// pauses 2 s standing. Gyro bias 0.01 rad/s on x and y, 0.005 on z at the start (the
/// paper re-estimates it at each trial's start), then drifting in-run by 0.003 rad/s per
/// minute on every axis (a warming MEMS gyro).
pub fn up_down() -> (Run, Poses) {
    let rate = 100.0;
    let standing = Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), 0.3);
    let prone = standing * Quat::from_axis_angle(Vec3::new(1.0, 0.0, 0.0), -core::f64::consts::FRAC_PI_2);
    let mut seq = Vec::new();
    for _ in 0..5 {
        seq.push((prone, 1.2, 2.0));
        seq.push((standing, 1.2, 2.0));
    }
    let poses = Poses::new(standing, 5.0, &seq);
    let p = Poses::new(standing, 5.0, &seq);
    let run = simulate(standing, poses.end + 1.0, rate, yei_noise(rate), move |t| {
        let (omega, moving) = p.rate(t);
        let bias = in_run_bias(t);
        let linear =
            if moving { Vec3::new(0.0, 3.0 * (t * 7.0).sin(), 2.0 * (t * 5.0).cos()) } else { Vec3::ZERO };
        Moment { omega, linear, bias, ..Moment::default() }
    });
    (run, poses)
}

/// The McGinnis protocols' gyro bias at time t (rad/s).
fn in_run_bias(t: f64) -> Vec3 {
    Vec3::new(0.01, 0.01, 0.005) + Vec3::new(1.0, 1.0, 1.0) * (0.003 * t / 60.0)
}

/// McGinnis 2014: rifle aiming. The IMU's e3 axis stays near vertical; from rest the
/// rifle is raised and aimed rapidly five times at targets ±40° in azimuth and a few
/// degrees in elevation, 0.5 s per turn, 2 s held on target, 2 s back at rest between.
/// Gyro bias as in [`up_down`]. Returns the run and the poses (for the rest times).
pub fn rifle_aiming() -> (Run, Poses) {
    let rate = 100.0;
    let z = Vec3::new(0.0, 0.0, 1.0);
    let rest = Quat::from_axis_angle(Vec3::new(1.0, 0.0, 0.0), 0.1);
    let mut seq = Vec::new();
    for k in 0..5 {
        let az = [-40.0f64, 30.0, 10.0, -20.0, 40.0][k].to_radians();
        let el = [3.0f64, -2.0, 5.0, 1.0, -4.0][k].to_radians();
        let aim = Quat::from_axis_angle(z, az) * rest * Quat::from_axis_angle(Vec3::new(1.0, 0.0, 0.0), el);
        seq.push((aim, 0.5, 2.0));
        seq.push((rest, 0.5, 2.0));
    }
    let poses = Poses::new(rest, 5.0, &seq);
    let p = Poses::new(rest, 5.0, &seq);
    let run = simulate(rest, poses.end + 1.0, rate, yei_noise(rate), move |t| {
        let (omega, moving) = p.rate(t);
        let bias = in_run_bias(t);
        let linear =
            if moving { Vec3::new(2.0 * (t * 9.0).sin(), 2.0 * (t * 6.0).cos(), 0.0) } else { Vec3::ZERO };
        Moment { omega, linear, bias, ..Moment::default() }
    });
    (run, poses)
}

/// Kim & Golnaraghi 2004, section 5: ADXRS150 gyros (0.05°/s/√Hz) and Silicon Designs
/// 1210 accelerometers (32 µg/√Hz) at 100 Hz; the drift δ "modelled as a slowly drifting
/// random process and added onto the rate gyro signal": here 0.5-1.5°/s per axis
/// wandering by ±0.3°/s over a minute. The motion: three-axis turns of about ±30° at
/// 0.2-0.5 Hz (the paper's pendulum-like platform). Returns the run and the true drift.
pub fn drifting_bias() -> (Run, Vec<Vec3>) {
    let rate = 100.0;
    let noise = (scale_of_density(0.05f64.to_radians(), rate), scale_of_density(32e-6 * G, rate), 0.0);
    let drift = |t: f64| {
        Vec3::new(1.0 + 0.3 * (t / 9.0).sin(), -0.5 + 0.3 * (t / 11.0).cos(), 1.5 + 0.3 * (t / 7.0).sin())
            * 1f64.to_radians()
    };
    let a = 30f64.to_radians();
    let run = simulate(Quat::IDENTITY, 60.0, rate, noise, move |t| {
        let omega = Vec3::new(
            a * 1.3 * (1.3 * t).cos(),
            a * 2.0 * (2.0 * t + 1.0).cos(),
            a * 3.0 * (3.0 * t + 2.0).cos() * 0.5,
        );
        Moment { omega, bias: drift(t), ..Moment::default() }
    });
    let truth = run.t.iter().map(|t| drift(*t)).collect();
    (run, truth)
}

/// GMVDK 2024 (section 3.2, Table 2): a MARG module (Yost 3-Space) held in five poses
/// at an undisturbed Location A, then carried to Location B above a steel bar (the paper
/// gives the bar, not the field it makes) and held in the same five poses there. Here:
/// 5 s still at home, the five poses at A (2 s turns, 5 s holds), 3 s to carry it to B
/// while the field changes by `distortion` (µT, earth frame), the five poses at B;
/// 100 Hz, YEI noise, gyro bias 0.3°/s. Returns the run and the time Location B's poses
/// start.
pub fn disturbed_pose_sequence(distortion: Vec3) -> (Run, f64) {
    let rate = 100.0;
    let home = Quat::from_axis_angle(Vec3::new(0.1, 0.2, 1.0), 0.4);
    let x = Vec3::new(1.0, 0.0, 0.0);
    let y = Vec3::new(0.0, 1.0, 0.0);
    let z = Vec3::new(0.0, 0.0, 1.0);
    let five = [
        home * Quat::from_axis_angle(z, 1.0),
        home * Quat::from_axis_angle(x, 0.6),
        home * Quat::from_axis_angle(y, -0.7),
        home * Quat::from_axis_angle(z, -0.8),
        home,
    ];
    let mut seq: Vec<(Quat, f64, f64)> = five.iter().map(|q| (*q, 2.0, 5.0)).collect();
    let carry = (5.0 + 35.0, 5.0 + 35.0 + 3.0);
    seq[4].2 += 3.0; // held at home pose while carried
    seq.extend(five.iter().map(|q| (*q, 2.0, 5.0)));
    let poses = Poses::new(home, 5.0, &seq);
    let bias = Vec3::new(0.3, -0.2, 0.25) * 1f64.to_radians();
    let run = simulate(home, poses.end, rate, yei_noise(rate), move |t| {
        let (omega, _) = poses.rate(t);
        let share = ((t - carry.0) / (carry.1 - carry.0)).clamp(0.0, 1.0);
        Moment { omega, field: FIELD + distortion * share, bias, ..Moment::default() }
    });
    (run, carry.1)
}
