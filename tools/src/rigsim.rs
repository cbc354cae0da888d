//! A rig simulator with exact truth: gloves (the hand and the proximal and middle
//! phalanges of four fingers, optionally the distal ones) and legs (pelvis, thigh, shank,
//! foot), written in the format of RIG-FORMAT.md ([`crate::rig`]).
//!
//! The body is a tree of segments. At the reference pose (the first
//! [`SimConfig::reference_s`] seconds, still) every segment frame is the same level frame
//! (x forward/distal, y left, z up), and every joint angle is zero. Then the motion
//! blends in: each joint angle is a bounded sum of random sinusoids (`lo + (hi − lo)·(1 +
//! tanh s)/2`), the root (hand or pelvis) turns and translates the same way, all on a
//! warped time τ(t) = ∫ a(t) dt whose activity `a` ramps smoothly between levels and to 0
//! for rests (everything then holds still). Joints:
//! - hinge (PIP, DIP, knee): `J = R(axis, θ)`, 2-DoF (MCP: abduction about the hand's z,
//!   then flexion about the phalanx's y; hip, ankle): `J = R(a1, α) R(a2, β)`; both
//!   times a laxity rotation about the constrained axes (each component bounded by
//!   [`SimConfig::laxity_deg`], plus [`SimConfig::axial_play_deg`] about an MCP's long
//!   axis).
//! - a sensor sits on its segment at a lever arm, turned by its mounting and by a
//!   soft-tissue wobble (each component bounded by [`SimConfig::wobble_deg`]):
//!   `q_sensor = q_segment ⊗ w ⊗ m`, so `q_segment = q_sensor ⊗ m⁻¹` at the reference pose.
//!
//! Readings: the gyroscope gives the rotation vector of each sample interval divided by
//! its length, `log(q(t−dt)⁻¹ q(t))/dt` (what a strapdown integration recovers exactly),
//! plus a per-sensor bias (each axis centred uniformly within ±(1 − d) of
//! [`SimConfig::bias_deg_s`] and drifting slowly by up to ±d of it, d =
//! [`SimConfig::bias_drift`], 0.2 in the presets, so no axis exceeds the bound), optionally scale and
//! axis errors ([`SimConfig::gyro_scale_pct`]), and white noise; the accelerometer the specific force at the sensor's position (second
//! difference of the position, so the lever arms' tangential and centripetal terms are
//! in it) plus noise; the magnetometer the earth's field, optionally with a dipole under
//! the desk and a hard-iron offset per sensor (the glove's electronics), plus noise. The
//! truth columns are the sensors' orientations; `movement` is 1 on the rows the rig score
//! counts (t ≥ 10 s). `rig.json` gets the true mountings (optionally turned by
//! [`SimConfig::mounting_error_deg`]) and the true axes in the sensor frames turned by
//! [`SimConfig::axis_error_deg`] about a random perpendicular direction.

use crate::eval::Recording;
use crate::rig::{JointKind, ReferencePose, RigJoint, RigRecording, RigSensor, RigSpec};
use orient::{Quat, Vec3};
use std::f64::consts::PI;

const G: f64 = 9.81;

/// Deterministic random numbers (SplitMix64).
#[derive(Clone, Debug)]
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        Rng(seed ^ 0x5851_f42d_4c95_7f2d)
    }
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    pub fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.uniform()
    }
    /// Standard normal (Box-Muller).
    pub fn gauss(&mut self) -> f64 {
        let u = self.uniform().max(1e-300);
        let v = self.uniform();
        (-2.0 * u.ln()).sqrt() * (2.0 * PI * v).cos()
    }
    pub fn gauss3(&mut self, s: f64) -> Vec3 {
        Vec3::new(self.gauss() * s, self.gauss() * s, self.gauss() * s)
    }
    /// A uniformly distributed unit vector.
    pub fn direction(&mut self) -> Vec3 {
        loop {
            let v = Vec3::new(self.gauss(), self.gauss(), self.gauss());
            if v.norm() > 1e-6 {
                return v.normalized();
            }
        }
    }
    /// A fresh generator for one part of the simulation, so that changing one part's
    /// draws leaves the others alone.
    pub fn fork(&mut self) -> Rng {
        Rng(self.next_u64())
    }
}

/// A smooth random signal of unit RMS: a sum of sinusoids with random frequencies in a
/// band, amplitudes falling as 1/f, random phases.
#[derive(Clone, Debug)]
pub struct Smooth {
    parts: Vec<(f64, f64, f64)>,
}

impl Smooth {
    pub fn new(rng: &mut Rng, f_lo: f64, f_hi: f64) -> Smooth {
        let n = 7;
        let mut parts: Vec<(f64, f64, f64)> = (0..n)
            .map(|_| {
                // Log-uniform frequency.
                let f = f_lo * (f_hi / f_lo).powf(rng.uniform());
                (2.0 * PI * f, rng.range(0.0, 2.0 * PI), rng.range(0.5, 1.0) / f.sqrt())
            })
            .collect();
        let power: f64 = parts.iter().map(|p| p.2 * p.2 / 2.0).sum();
        for p in &mut parts {
            p.2 /= power.sqrt();
        }
        Smooth { parts }
    }
    pub fn at(&self, tau: f64) -> f64 {
        self.parts.iter().map(|(w, ph, a)| a * (w * tau + ph).sin()).sum()
    }
}

/// A smooth signal bounded to [lo, hi]: `lo + (hi − lo)(1 + tanh(gain·s))/2`.
#[derive(Clone, Debug)]
pub struct Bounded {
    s: Smooth,
    lo: f64,
    hi: f64,
    gain: f64,
}

impl Bounded {
    pub fn new(rng: &mut Rng, band: (f64, f64), lo: f64, hi: f64) -> Bounded {
        Bounded { s: Smooth::new(rng, band.0, band.1), lo, hi, gain: 0.9 }
    }
    pub fn at(&self, tau: f64) -> f64 {
        self.lo + (self.hi - self.lo) * 0.5 * (1.0 + (self.gain * self.s.at(tau)).tanh())
    }
}

/// The quintic smoothstep 6u⁵ − 15u⁴ + 10u³ on [0, 1] (C² at both ends), clamped.
fn smoothstep(u: f64) -> f64 {
    let u = u.clamp(0.0, 1.0);
    u * u * u * (u * (6.0 * u - 15.0) + 10.0)
}

/// ∫₀ᵘ smoothstep = u⁶ − 3u⁵ + 5u⁴/2 for u in [0, 1].
fn smoothstep_integral(u: f64) -> f64 {
    let u = u.clamp(0.0, 1.0);
    u * u * u * u * (u * (u - 3.0) + 2.5)
}

/// The activity a(t) (levels held between knots, quintic ramps of `ramp` seconds after
/// each knot) and the warped time τ(t) = ∫₀ᵗ a.
#[derive(Clone, Debug)]
struct Schedule {
    /// (knot time, level after it, τ at the knot).
    knots: Vec<(f64, f64, f64)>,
    ramp: f64,
}

impl Schedule {
    fn new(levels: &[(f64, f64)], ramp: f64) -> Schedule {
        let mut knots: Vec<(f64, f64, f64)> = Vec::new();
        for (k, &(t, level)) in levels.iter().enumerate() {
            let tau = match k {
                0 => 0.0,
                _ => {
                    let (t0, to, tau0) = knots[k - 1];
                    let from = if k >= 2 { knots[k - 2].1 } else { 0.0 };
                    tau0 + Schedule::gain(t0, from, to, ramp, t)
                }
            };
            knots.push((t, level, tau));
        }
        Schedule { knots, ramp }
    }

    /// ∫ a over [t0, t] after a knot at t0 that ramps from `from` to `to`.
    fn gain(t0: f64, from: f64, to: f64, ramp: f64, t: f64) -> f64 {
        let d = (t - t0).max(0.0);
        let u = (d / ramp).min(1.0);
        from * d + (to - from) * (ramp * smoothstep_integral(u) + (d - ramp).max(0.0))
    }

    fn locate(&self, t: f64) -> Option<usize> {
        let k = self.knots.partition_point(|k| k.0 <= t);
        k.checked_sub(1)
    }

    fn activity(&self, t: f64) -> f64 {
        match self.locate(t) {
            None => 0.0,
            Some(k) => {
                let from = if k == 0 { 0.0 } else { self.knots[k - 1].1 };
                let (t0, to, _) = self.knots[k];
                from + (to - from) * smoothstep((t - t0) / self.ramp)
            }
        }
    }

    fn tau(&self, t: f64) -> f64 {
        match self.locate(t) {
            None => 0.0,
            Some(k) => {
                let from = if k == 0 { 0.0 } else { self.knots[k - 1].1 };
                let (t0, to, tau0) = self.knots[k];
                tau0 + Schedule::gain(t0, from, to, self.ramp, t)
            }
        }
    }
}

/// Which body the rig is on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Body {
    /// A right hand: the hand and the proximal and middle phalanges of the index, middle,
    /// ring and little fingers; with `dip`, the distal phalanges too.
    Glove { dip: bool },
    /// A left leg: pelvis, thigh (hip 2-DoF), shank (knee hinge), foot (ankle 2-DoF).
    Leg,
}

/// What to simulate. [`SimConfig::preset`] gives the cases.
#[derive(Clone, Debug, PartialEq)]
pub struct SimConfig {
    pub body: Body,
    pub rate_hz: f64,
    pub duration_s: f64,
    pub seed: u64,
    /// Faster and wider motion (frequencies doubled, ranges wider, more acceleration).
    pub vigorous: bool,
    /// The fraction of the moving time the palm (the pelvis, on a leg) is turned
    /// sideways, its lateral axes near vertical; 0 for ordinary motion.
    pub sideways: f64,
    /// Bound on each axis of each sensor's gyroscope bias, deg/s.
    pub bias_deg_s: f64,
    /// How far each axis's bias drifts, a fraction of [`SimConfig::bias_deg_s`] from 0 to
    /// 1: each axis is centred within ±(1 − this) of the bound and moves within ± this of
    /// it over one to ten minutes; the presets' 0.2; 0 for a constant bias.
    pub bias_drift: f64,
    /// Angle by which each axis in rig.json is off the true one, degrees.
    pub axis_error_deg: f64,
    /// Angle by which each mounting in rig.json is off the true one, degrees.
    pub mounting_error_deg: f64,
    /// Joint laxity about each constrained axis (bound), degrees.
    pub laxity_deg: f64,
    /// Extra axial play at the MCP joints (bound), degrees.
    pub axial_play_deg: f64,
    /// Soft-tissue wobble of each sensor on its segment (bound per axis), degrees.
    pub wobble_deg: f64,
    /// Gyroscope scale and axis errors (percent): each sensor's reading is `(I + E) ω`
    /// with `E`'s diagonal uniform within ± this and its other entries within ± half of
    /// it (a MEMS gyroscope's sensitivity tolerance and cross-axis sensitivity, 1-2 %
    /// after soldering); 0 for none, the presets' value.
    pub gyro_scale_pct: f64,
    /// White noise standard deviations: gyroscope rad/s, accelerometer m/s², magnetometer µT.
    pub gyro_noise: f64,
    pub accel_noise: f64,
    pub mag_noise: f64,
    /// A magnet under the desk (a dipole below the workspace) and hard-iron offsets from
    /// the glove's electronics.
    pub magnet: bool,
    /// Length of the still reference pose at the start, seconds.
    pub reference_s: f64,
    /// Rests between moving episodes (of 10-30 s): the mean time (s) each holds still,
    /// uniform within ±50 %, after a ramp of 1 s down; 0 for no rests.
    pub rest_s: f64,
}

/// The presets: the cases of issue 42's table (`100hz`, `60hz-vigorous`, `palm-sideways`,
/// `bias-3dps`, `axes-5deg-off`, gloves of 10 minutes) and a leg (`leg`).
pub const PRESETS: [&str; 6] =
    ["100hz", "60hz-vigorous", "palm-sideways", "bias-3dps", "axes-5deg-off", "leg"];

/// The first of `cases` that names no preset, as a tool's usage error says it.
pub fn unknown_preset(cases: &[String]) -> Option<String> {
    let case = cases.iter().find(|c| !PRESETS.contains(&c.as_str()))?;
    Some(format!("unknown case '{case}' ({})", PRESETS.join(", ")))
}

impl SimConfig {
    /// A 10-minute glove at 100 Hz: bias to 1 deg/s, laxity 3 deg, axial play 4 deg,
    /// wobble 1.5 deg, axes and mountings true, a magnet under the desk.
    pub fn glove(seed: u64) -> SimConfig {
        SimConfig {
            body: Body::Glove { dip: false },
            rate_hz: 100.0,
            duration_s: 600.0,
            seed,
            vigorous: false,
            sideways: 0.0,
            bias_deg_s: 1.0,
            bias_drift: 0.2,
            axis_error_deg: 0.0,
            mounting_error_deg: 0.0,
            laxity_deg: 3.0,
            axial_play_deg: 4.0,
            wobble_deg: 1.5,
            gyro_scale_pct: 0.0,
            gyro_noise: 0.1f64.to_radians(),
            accel_noise: 0.05,
            mag_noise: 0.5,
            magnet: true,
            reference_s: 5.0,
            rest_s: 2.5,
        }
    }

    /// One of [`PRESETS`].
    pub fn preset(name: &str, seed: u64) -> Option<SimConfig> {
        let base = SimConfig::glove(seed);
        Some(match name {
            "100hz" => base,
            "60hz-vigorous" => SimConfig { rate_hz: 60.0, vigorous: true, ..base },
            "palm-sideways" => SimConfig { sideways: 0.45, ..base },
            "bias-3dps" => SimConfig { bias_deg_s: 3.0, ..base },
            "axes-5deg-off" => SimConfig { axis_error_deg: 5.0, ..base },
            "leg" => {
                SimConfig { body: Body::Leg, axial_play_deg: 0.0, wobble_deg: 2.0, magnet: false, ..base }
            }
            _ => return None,
        })
    }
}

/// How a segment hangs on its parent.
#[derive(Clone, Debug)]
enum Hang {
    Root,
    /// The hinge axis (segment frames), its angle.
    Hinge(Vec3, Bounded),
    /// The first axis (parent's segment frame), the second (child's), their angles.
    TwoDof(Vec3, Vec3, Bounded, Bounded),
}

#[derive(Clone, Debug)]
struct Segment {
    name: String,
    parent: Option<usize>,
    hang: Hang,
    /// The joint centre in the parent's segment frame (this segment's origin).
    offset: Vec3,
    /// The sensor's position in this segment's frame.
    lever: Vec3,
    /// Sensor to segment.
    mounting: Quat,
    /// Laxity rotation vector components: (axis, bounded angle) in the child's frame.
    laxity: Vec<(Vec3, Bounded)>,
    /// Soft-tissue wobble, three components (segment frame).
    wobble: [Bounded; 3],
    /// Bias: constant part and drift (rad/s), in the sensor frame.
    bias0: Vec3,
    drift: [Bounded; 3],
    /// Hard-iron offset (µT, sensor frame).
    hard_iron: Vec3,
}

/// The root's motion.
#[derive(Clone, Debug)]
struct RootMotion {
    yaw0: f64,
    yaw: Bounded,
    pitch: Bounded,
    roll: Bounded,
    /// Sideways phases: an indicator p in [0, 1] and the roll held while sideways.
    side: Option<(Smooth, f64, Bounded)>,
    pos0: Vec3,
    pos: [Bounded; 3],
}

/// One instant of the rig.
#[derive(Clone, Debug)]
pub struct Pose {
    pub segments: Vec<Quat>,
    pub sensors: Vec<Quat>,
    pub positions: Vec<Vec3>,
}

/// A simulated rig: the description, the motion model, and the run's data.
pub struct Simulation {
    pub config: SimConfig,
    segments: Vec<Segment>,
    root: RootMotion,
    schedule: Schedule,
    /// The reference pose ends here; the motion blends in over the next seconds.
    blend: (f64, f64),
    field: Vec3,
    magnet: Option<(Vec3, Vec3)>,
}

/// The output of [`Simulation::run`].
pub struct SimRig {
    pub recording: RigRecording,
    /// Each segment's true orientation, `[sensor][row]`.
    pub segment_truth: Vec<Vec<Quat>>,
    /// Each sensor's true gyroscope bias (rad/s), `[sensor][row]`.
    pub bias: Vec<Vec<Vec3>>,
    /// True axes in the sensor frames, per joint (axis_parent, axis_child).
    pub true_axes: Vec<(Vec3, Vec3)>,
    /// The activity per row (0 at rest).
    pub activity: Vec<f64>,
}

fn x() -> Vec3 {
    Vec3::new(1.0, 0.0, 0.0)
}
fn y() -> Vec3 {
    Vec3::new(0.0, 1.0, 0.0)
}
fn z() -> Vec3 {
    Vec3::new(0.0, 0.0, 1.0)
}
fn deg(d: f64) -> f64 {
    d.to_radians()
}

/// A command line's seeds, `A-B` or `A`: the first and the last.
pub fn seed_range(v: &str) -> (u64, u64) {
    let (a, b) = v.split_once('-').unwrap_or((v, v));
    (a.parse().expect("a seed"), b.parse().expect("a seed"))
}

/// A `--bias-drift F` argument ([`SimConfig::bias_drift`]): a number from 0 to 1.
pub fn bias_drift_arg(v: &str) -> Result<f64, String> {
    match v.parse::<f64>() {
        Ok(f) if (0.0..=1.0).contains(&f) => Ok(f),
        _ => Err(format!("--bias-drift: '{v}' is not a number from 0 to 1")),
    }
}

/// The rotation by the rotation vector `v`.
pub fn exp(v: Vec3) -> Quat {
    let a = v.norm();
    if a < 1e-300 {
        return Quat::IDENTITY;
    }
    Quat::from_axis_angle(v, a)
}

/// The rotation vector of `q` (angle in [0, π]).
pub fn log(q: Quat) -> Vec3 {
    let q = if q.w < 0.0 { q.scale(-1.0) } else { q };
    let s = q.vector().norm();
    if s < 1e-300 {
        return Vec3::ZERO;
    }
    q.vector() * (2.0 * libm::atan2(s, q.w) / s)
}

/// A rotation by `angle` about a direction perpendicular to `v`, random.
fn perpendicular_turn(rng: &mut Rng, v: Vec3, angle: f64) -> Quat {
    let p = v.cross(rng.direction());
    Quat::from_axis_angle(if p.norm() > 1e-6 { p } else { v.cross(x() + z() * 0.5) }, angle)
}

impl Simulation {
    pub fn new(config: SimConfig) -> Simulation {
        let mut rng = Rng::new(config.seed);
        let mut motion = rng.fork();
        let mut misc = rng.fork();
        let speed = if config.vigorous { 2.2 } else { 1.0 };
        let band = |lo: f64, hi: f64| (lo * speed, hi * speed);
        let wide = |lo: f64, hi: f64| if config.vigorous { (lo * 1.15, hi * 1.15) } else { (lo, hi) };
        let mut segs: Vec<Segment> = Vec::new();
        let mut add = |name: String,
                       parent: Option<usize>,
                       hang: Hang,
                       offset: Vec3,
                       lever: Vec3,
                       laxity_axes: Vec<(Vec3, f64)>,
                       rng: &mut Rng| {
            let mounting = Quat::from_axis_angle(z(), rng.range(-PI, PI))
                * Quat::from_axis_angle(rng.direction(), deg(rng.range(0.0, 20.0)));
            let laxity = laxity_axes
                .into_iter()
                .map(|(a, b)| (a, Bounded::new(rng, band(0.2, 2.0), -deg(b), deg(b))))
                .collect();
            let w = deg(config.wobble_deg);
            let wobble = [0, 1, 2].map(|_| Bounded::new(rng, band(0.5, 4.0), -w, w));
            let b = deg(config.bias_deg_s);
            let (d, r) = (config.bias_drift, 1.0 - config.bias_drift);
            let bias0 = Vec3::new(rng.range(-r, r), rng.range(-r, r), rng.range(-r, r)) * b;
            let drift = [0, 1, 2].map(|_| Bounded::new(rng, (1.0 / 600.0, 1.0 / 60.0), -d * b, d * b));
            let hard_iron = if config.magnet { rng.direction() * rng.range(0.5, 3.0) } else { Vec3::ZERO };
            segs.push(Segment {
                name,
                parent,
                hang,
                offset,
                lever,
                mounting,
                laxity,
                wobble,
                bias0,
                drift,
                hard_iron,
            });
            segs.len() - 1
        };
        let lax = config.laxity_deg;
        match config.body {
            Body::Glove { dip } => {
                let hand = add(
                    "hand".into(),
                    None,
                    Hang::Root,
                    Vec3::ZERO,
                    Vec3::new(0.04, 0.0, 0.02),
                    vec![],
                    &mut motion,
                );
                // Index, middle, ring, little: MCP position across the hand, phalanx lengths.
                let fingers = [
                    ("index", 0.028, 0.045, 0.026, 0.019),
                    ("middle", 0.008, 0.050, 0.030, 0.020),
                    ("ring", -0.012, 0.047, 0.029, 0.020),
                    ("little", -0.030, 0.037, 0.021, 0.018),
                ];
                for (k, (f, across, l1, l2, l3)) in fingers.into_iter().enumerate() {
                    let mcp_x = 0.085 - 0.005 * k as f64;
                    let abd = if k == 0 {
                        (-15.0, 12.0)
                    } else if k == 3 {
                        (-20.0, 8.0)
                    } else {
                        (-10.0, 10.0)
                    };
                    let (a0, a1) = wide(abd.0, abd.1);
                    let (f0, f1) = wide(-15.0, 80.0);
                    let prox = add(
                        format!("{f}_proximal"),
                        Some(hand),
                        Hang::TwoDof(
                            z(),
                            y(),
                            Bounded::new(&mut motion, band(0.08, 0.8), deg(a0), deg(a1)),
                            Bounded::new(&mut motion, band(0.08, 1.0), deg(f0), deg(f1)),
                        ),
                        Vec3::new(mcp_x, across, 0.0),
                        Vec3::new(0.5 * l1, 0.0, 0.009),
                        vec![(x(), lax + config.axial_play_deg)],
                        &mut motion,
                    );
                    let (p0, p1) = wide(0.0, 90.0);
                    let mid = add(
                        format!("{f}_middle"),
                        Some(prox),
                        Hang::Hinge(
                            y(),
                            Bounded::new(&mut motion, band(0.08, 1.0), deg(p0), deg(p1.min(105.0))),
                        ),
                        Vec3::new(l1, 0.0, 0.0),
                        Vec3::new(0.5 * l2, 0.0, 0.008),
                        vec![(x(), lax), (z(), lax)],
                        &mut motion,
                    );
                    if dip {
                        add(
                            format!("{f}_distal"),
                            Some(mid),
                            Hang::Hinge(y(), Bounded::new(&mut motion, band(0.08, 1.0), deg(0.0), deg(70.0))),
                            Vec3::new(l2, 0.0, 0.0),
                            Vec3::new(0.5 * l3, 0.0, 0.007),
                            vec![(x(), lax), (z(), lax)],
                            &mut motion,
                        );
                    }
                }
            }
            Body::Leg => {
                let pelvis = add(
                    "pelvis".into(),
                    None,
                    Hang::Root,
                    Vec3::ZERO,
                    Vec3::new(-0.1, 0.0, 0.0),
                    vec![],
                    &mut motion,
                );
                let thigh = add(
                    "thigh".into(),
                    Some(pelvis),
                    Hang::TwoDof(
                        y(),
                        x(),
                        Bounded::new(&mut motion, band(0.05, 0.7), deg(-95.0), deg(20.0)),
                        Bounded::new(&mut motion, band(0.05, 0.5), deg(-10.0), deg(30.0)),
                    ),
                    Vec3::new(0.0, 0.09, -0.08),
                    Vec3::new(0.07, 0.0, -0.2),
                    vec![(z(), lax)],
                    &mut motion,
                );
                let shank = add(
                    "shank".into(),
                    Some(thigh),
                    Hang::Hinge(y(), Bounded::new(&mut motion, band(0.05, 0.8), deg(0.0), deg(120.0))),
                    Vec3::new(0.0, 0.0, -0.45),
                    Vec3::new(0.05, 0.0, -0.2),
                    vec![(x(), lax), (z(), lax)],
                    &mut motion,
                );
                add(
                    "foot".into(),
                    Some(shank),
                    Hang::TwoDof(
                        y(),
                        x(),
                        Bounded::new(&mut motion, band(0.05, 0.8), deg(-20.0), deg(40.0)),
                        Bounded::new(&mut motion, band(0.05, 0.6), deg(-15.0), deg(20.0)),
                    ),
                    Vec3::new(0.0, 0.0, -0.43),
                    Vec3::new(0.08, 0.0, 0.03),
                    vec![(z(), lax)],
                    &mut motion,
                );
            }
        }
        let leg = config.body == Body::Leg;
        let (yaw_a, pitch_a, roll_a) = if leg {
            (90.0, 15.0, 10.0)
        } else if config.vigorous {
            (100.0, 50.0, 85.0)
        } else {
            (80.0, 40.0, 75.0)
        };
        let side = (config.sideways > 0.0).then(|| {
            let s = Smooth::new(&mut motion, 1.0 / 80.0, 1.0 / 15.0);
            // A unit-RMS sum of sinusoids is near normal: the threshold that leaves
            // `sideways` of the time above it.
            let c = normal_quantile(1.0 - config.sideways);
            (s, c, Bounded::new(&mut motion, band(0.05, 0.5), deg(75.0), deg(100.0)))
        });
        let pa = if config.vigorous { 0.2 } else { 0.12 };
        let root_motion = RootMotion {
            yaw0: motion.range(-PI, PI),
            yaw: Bounded::new(&mut motion, band(0.01, 0.3), -deg(yaw_a), deg(yaw_a)),
            pitch: Bounded::new(&mut motion, band(0.03, 0.6), -deg(pitch_a), deg(pitch_a)),
            roll: Bounded::new(&mut motion, band(0.03, 0.6), -deg(roll_a), deg(roll_a)),
            side,
            pos0: if leg { Vec3::new(0.0, 0.0, 1.0) } else { Vec3::new(0.0, 0.0, 0.25) },
            pos: [
                Bounded::new(&mut motion, band(0.05, 1.0), -pa, pa),
                Bounded::new(&mut motion, band(0.05, 1.0), -pa, pa),
                Bounded::new(&mut motion, band(0.05, 1.0), -0.5 * pa, 0.5 * pa),
            ],
        };
        // Moving episodes and rests after the reference pose.
        let mut levels = vec![];
        let mut t = config.reference_s;
        let ramp = 1.0;
        while t < config.duration_s + 10.0 {
            let lv = if config.vigorous { misc.range(1.0, 1.5) } else { misc.range(0.6, 1.3) };
            levels.push((t, lv));
            let mean_move = 20.0;
            t += misc.range(0.5, 1.5) * mean_move;
            if config.rest_s > 0.0 {
                levels.push((t, 0.0));
                t += ramp + misc.range(0.5, 1.5) * config.rest_s;
            }
        }
        let schedule = Schedule::new(&levels, ramp);
        let field = Vec3::new(0.0, 49.0 * deg(65.0).cos(), -49.0 * deg(65.0).sin());
        let magnet = config.magnet.then(|| {
            (
                root_motion.pos0 + Vec3::new(misc.range(-0.1, 0.1), misc.range(-0.1, 0.1), -0.2),
                misc.direction() * 1.5,
            )
        });
        Simulation {
            blend: (config.reference_s, config.reference_s + 2.0),
            config,
            segments: segs,
            root: root_motion,
            schedule,
            field,
            magnet,
        }
    }

    /// How far the motion has blended in from the reference pose (0 there, 1 after).
    fn blend(&self, t: f64) -> f64 {
        smoothstep((t - self.blend.0) / (self.blend.1 - self.blend.0))
    }

    /// The rig at time t.
    pub fn pose(&self, t: f64) -> Pose {
        let b = self.blend(t);
        let tau = self.schedule.tau(t);
        let r = &self.root;
        let mut roll = r.roll.at(tau);
        let mut pitch = r.pitch.at(tau);
        if let Some((s, c, side_roll)) = &r.side {
            let p = 0.5 * (1.0 + (3.0 * (s.at(tau) - c)).tanh());
            roll = (1.0 - p) * roll + p * side_roll.at(tau);
            pitch *= 1.0 - 0.6 * p;
        }
        let q_root = Quat::from_axis_angle(z(), r.yaw0 + b * r.yaw.at(tau))
            * Quat::from_axis_angle(y(), b * pitch)
            * Quat::from_axis_angle(x(), b * roll);
        let p_root = r.pos0 + Vec3::new(r.pos[0].at(tau), r.pos[1].at(tau), r.pos[2].at(tau)) * b;
        let n = self.segments.len();
        let mut pose = Pose {
            segments: Vec::with_capacity(n),
            sensors: Vec::with_capacity(n),
            positions: Vec::with_capacity(n),
        };
        let mut origins: Vec<Vec3> = Vec::with_capacity(n);
        for s in &self.segments {
            let (q, o) = match (&s.hang, s.parent) {
                (Hang::Root, _) | (_, None) => (q_root, p_root),
                (hang, Some(p)) => {
                    let joint = match hang {
                        Hang::Hinge(a, th) => Quat::from_axis_angle(*a, b * th.at(tau)),
                        Hang::TwoDof(a1, a2, al, be) => {
                            Quat::from_axis_angle(*a1, b * al.at(tau))
                                * Quat::from_axis_angle(*a2, b * be.at(tau))
                        }
                        Hang::Root => unreachable!(),
                    };
                    let lax = s.laxity.iter().fold(Vec3::ZERO, |v, (a, l)| v + *a * (b * l.at(tau)));
                    let q = (pose.segments[p] * joint * exp(lax)).normalized();
                    (q, origins[p] + pose.segments[p].rotate(s.offset))
                }
            };
            let w = Vec3::new(s.wobble[0].at(tau), s.wobble[1].at(tau), s.wobble[2].at(tau)) * b;
            pose.sensors.push((q * exp(w) * s.mounting).normalized());
            pose.positions.push(o + q.rotate(s.lever));
            pose.segments.push(q);
            origins.push(o);
        }
        pose
    }

    /// Sensor `i`'s gyroscope bias (rad/s, sensor frame) at time t.
    pub fn bias(&self, i: usize, t: f64) -> Vec3 {
        let s = &self.segments[i];
        s.bias0 + Vec3::new(s.drift[0].at(t), s.drift[1].at(t), s.drift[2].at(t))
    }

    /// The magnetic field (µT, ENU) at a position.
    pub fn field_at(&self, p: Vec3) -> Vec3 {
        match self.magnet {
            None => self.field,
            Some((at, m)) => {
                let r = p - at;
                let d = r.norm().max(0.05);
                let u = r * (1.0 / d);
                // µ0/4π = 1e-7 T·m/A; in µT: 0.1 (3 (m·u) u − m) / d³.
                self.field + (u * (3.0 * m.dot(u)) - m) * (0.1 / (d * d * d))
            }
        }
    }

    /// The description (rig.json) with the configured errors in axes and mountings.
    fn spec(&self) -> (RigSpec, Vec<(Vec3, Vec3)>) {
        let mut rng = Rng::new(self.config.seed ^ 0xa4e5);
        let sensors: Vec<RigSensor> = self
            .segments
            .iter()
            .map(|s| {
                let m = if self.config.mounting_error_deg > 0.0 {
                    (Quat::from_axis_angle(rng.direction(), deg(self.config.mounting_error_deg)) * s.mounting)
                        .normalized()
                } else {
                    s.mounting
                };
                RigSensor { name: s.name.clone(), file: format!("{}.csv", s.name), mounting: m }
            })
            .collect();
        let mut joints = Vec::new();
        let mut true_axes = Vec::new();
        for (c, s) in self.segments.iter().enumerate() {
            let Some(p) = s.parent else { continue };
            let (kind, a_p, a_c) = match &s.hang {
                Hang::Hinge(a, _) => (JointKind::Hinge, *a, *a),
                Hang::TwoDof(a1, a2, _, _) => (JointKind::TwoDof, *a1, *a2),
                Hang::Root => continue,
            };
            // Segment frame to sensor frame: v_sensor = m⁻¹ v_segment.
            let ap = self.segments[p].mounting.rotate_inverse(a_p);
            let ac = s.mounting.rotate_inverse(a_c);
            true_axes.push((ap, ac));
            let e = deg(self.config.axis_error_deg);
            let (gp, gc) = if e > 0.0 {
                (
                    perpendicular_turn(&mut rng, ap, e).rotate(ap),
                    perpendicular_turn(&mut rng, ac, e).rotate(ac),
                )
            } else {
                (ap, ac)
            };
            let name = s.name.split('_').next().unwrap_or("").to_string();
            let jname = match (self.config.body, s.name.rsplit('_').next()) {
                (Body::Glove { .. }, Some("proximal")) => format!("{name}_mcp"),
                (Body::Glove { .. }, Some("middle")) => format!("{name}_pip"),
                (Body::Glove { .. }, Some("distal")) => format!("{name}_dip"),
                (_, _) => match s.name.as_str() {
                    "thigh" => "hip".into(),
                    "shank" => "knee".into(),
                    _ => "ankle".into(),
                },
            };
            joints.push(RigJoint { name: jname, kind, parent: p, child: c, axis_parent: gp, axis_child: gc });
        }
        let note = match self.config.body {
            Body::Glove { .. } => "hand level, fingers straight",
            Body::Leg => "standing, pelvis level, foot flat",
        };
        let spec = RigSpec {
            rate_hz: self.config.rate_hz,
            reference_pose: Some(ReferencePose {
                start: 0.0,
                end: self.config.reference_s,
                note: note.into(),
            }),
            sensors,
            joints,
        };
        (spec, true_axes)
    }

    /// Simulates the whole recording.
    pub fn run(&self) -> SimRig {
        let c = &self.config;
        let dt = 1.0 / c.rate_hz;
        let rows = (c.duration_s * c.rate_hz).round() as usize;
        let n = self.segments.len();
        let mut noise = Rng::new(c.seed ^ 0x7e57_0001);
        // Each sensor's scale and axis errors, from a stream of their own so that the
        // rest of a seed's recording does not depend on them.
        let mut scale_rng = Rng::new(c.seed ^ 0x5ca1_e000);
        let pct = c.gyro_scale_pct / 100.0;
        let scale: Vec<[[f64; 3]; 3]> = (0..n)
            .map(|_| {
                core::array::from_fn(|i| {
                    core::array::from_fn(|j| {
                        if i == j {
                            scale_rng.range(-pct, pct)
                        } else {
                            scale_rng.range(-0.5 * pct, 0.5 * pct)
                        }
                    })
                })
            })
            .collect();
        let (spec, true_axes) = self.spec();
        let mut sensors: Vec<Recording> = (0..n)
            .map(|_| Recording {
                t: Vec::with_capacity(rows),
                gyro: Vec::with_capacity(rows),
                accel: Vec::with_capacity(rows),
                mag: Vec::with_capacity(rows),
                truth: Vec::with_capacity(rows),
                movement: Vec::with_capacity(rows),
            })
            .collect();
        let mut segment_truth: Vec<Vec<Quat>> = (0..n).map(|_| Vec::with_capacity(rows)).collect();
        let mut bias: Vec<Vec<Vec3>> = (0..n).map(|_| Vec::with_capacity(rows)).collect();
        let mut activity = Vec::with_capacity(rows);
        // Second differences of position with this step: truncation ~h²·p''''/12 and
        // rounding ~1e-16/h², both far below the accelerometer noise.
        let h = 2e-3;
        let mut prev = self.pose(-dt);
        for i in 0..rows {
            let t = i as f64 / c.rate_hz;
            let now = self.pose(t);
            let (before, after) = (self.pose(t - h), self.pose(t + h));
            for s in 0..n {
                let r = &mut sensors[s];
                let q = now.sensors[s];
                let omega = log(prev.sensors[s].conj() * q) * (1.0 / dt);
                let b = self.bias(s, t);
                let acc =
                    (after.positions[s] - now.positions[s] * 2.0 + before.positions[s]) * (1.0 / (h * h));
                let f = q.rotate_inverse(acc + Vec3::new(0.0, 0.0, G));
                let m = q.rotate_inverse(self.field_at(now.positions[s])) + self.segments[s].hard_iron;
                r.t.push(t);
                let e = &scale[s];
                let scaled = Vec3::new(
                    e[0][0] * omega.x + e[0][1] * omega.y + e[0][2] * omega.z,
                    e[1][0] * omega.x + e[1][1] * omega.y + e[1][2] * omega.z,
                    e[2][0] * omega.x + e[2][1] * omega.y + e[2][2] * omega.z,
                );
                r.gyro.push(omega + scaled + b + noise.gauss3(c.gyro_noise));
                r.accel.push(f + noise.gauss3(c.accel_noise));
                r.mag.push(m + noise.gauss3(c.mag_noise));
                r.truth.push(q);
                r.movement.push(t >= crate::rig::SCORED_FROM);
                segment_truth[s].push(now.segments[s]);
                bias[s].push(b);
            }
            activity.push(self.schedule.activity(t) * self.blend(t));
            prev = now;
        }
        SimRig { recording: RigRecording { spec, sensors }, segment_truth, bias, true_axes, activity }
    }

    /// The segments' names, in sensor order.
    pub fn names(&self) -> Vec<&str> {
        self.segments.iter().map(|s| s.name.as_str()).collect()
    }
}

/// The standard normal quantile (Acklam's rational approximation, |error| < 1.2e-9).
fn normal_quantile(p: f64) -> f64 {
    let p = p.clamp(1e-12, 1.0 - 1e-12);
    let a = [
        -3.969683028665376e1,
        2.209460984245205e2,
        -2.759285104469687e2,
        1.38357751867269e2,
        -3.066479806614716e1,
        2.506628277459239,
    ];
    let b = [
        -5.447609879822406e1,
        1.615858368580409e2,
        -1.556989798598866e2,
        6.680131188771972e1,
        -1.328068155288572e1,
    ];
    let c = [
        -7.784894002430293e-3,
        -3.223964580411365e-1,
        -2.400758277161838,
        -2.549732539343734,
        4.374664141464968,
        2.938163982698783,
    ];
    let d = [7.784695709041462e-3, 3.224671290700398e-1, 2.445134137142996, 3.754408661907416];
    let tail = |q: f64| {
        (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5])
            / ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1.0)
    };
    if p < 0.02425 {
        tail((-2.0 * p.ln()).sqrt())
    } else if p > 1.0 - 0.02425 {
        -tail((-2.0 * (1.0 - p).ln()).sqrt())
    } else {
        let q = p - 0.5;
        let r = q * q;
        (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q
            / (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1.0)
    }
}

/// The fraction of rows in which the hinge axes of the PIP joints (or every hinge) are
/// more than `deg` from horizontal, in the truth (segment frames).
pub fn vertical_hinge_fraction(sim: &SimRig, deg: f64) -> f64 {
    let spec = &sim.recording.spec;
    let (mut on, mut n) = (0usize, 0usize);
    for (j, joint) in spec.joints.iter().enumerate() {
        if joint.kind != JointKind::Hinge {
            continue;
        }
        let axis = sim.true_axes[j].0;
        for q in &sim.recording.sensors[joint.parent].truth {
            let e = q.rotate(axis);
            let elevation = e.z.abs().clamp(0.0, 1.0).asin().to_degrees();
            on += usize::from(elevation > deg);
            n += 1;
        }
    }
    on as f64 / n.max(1) as f64
}
