//! orient's recommended filter: a gyroscope strapdown corrected by a low-passed
//! accelerometer in a quasi-inertial frame and by a gated magnetometer heading, with gyro
//! bias estimation at rest and in motion.
//!
//! The seed filters correct the attitude towards each accelerometer sample, so every
//! linear acceleration tilts them, and towards each magnetometer sample, so every nearby
//! magnet turns them. This filter is built on three facts instead:
//!
//! 1. Over a few seconds linear acceleration averages out *in the earth frame* (a hand
//!    cannot keep accelerating one way), while gravity does not. So the accelerometer
//!    is rotated into a frame that follows the gyroscope alone (the quasi-inertial frame
//!    I, which drifts only slowly) and low-passed there; the inclination is corrected
//!    to the filtered vector. Fast translation (BROAD trial 15) and tapping (24) then
//!    barely tilt the estimate. The idea is that of VQF (D. Laidig, T. Seel, "VQF:
//!    Highly accurate IMU orientation estimation with bias estimation and magnetic
//!    disturbance rejection", Information Fusion 91, 2023); the implementation and the
//!    mechanisms below are orient's own.
//! 2. At rest the gyroscope reads its bias. Rest is detected from the spread of the
//!    gyroscope and accelerometer around their own low-passed values; the bias then
//!    follows the low-passed gyroscope. In motion, the accelerometer correction that the
//!    filter keeps applying is the drift a bias error causes: a Kalman filter on the bias
//!    takes it as a measurement of the bias's horizontal part in the earth frame
//!    (`motion_bias`, VQF's formulation), so every sensor axis that turns through the
//!    horizontal is learned, and the vertical one of the moment is not.
//! 3. The undisturbed earth field has a fixed norm and dip. A reading whose norm or dip
//!    leaves the reference is not used for heading; the gyroscope holds the heading
//!    meanwhile, and corrections resume at the slow heading rate, so there is no jump.
//!    A magnet attached to the sensor adds a constant vector in the *sensor* frame
//!    (hard iron). While the field is disturbed the filter estimates that vector as the
//!    reading minus the reference field seen at the current orientation; when the
//!    estimate stays consistent for `hard_iron_time` and the compensated field passes
//!    the norm and dip tests, the compensated field is used. A disturbance fixed in
//!    the room is not a constant sensor-frame vector once the sensor moves, so it
//!    fails the consistency test or, later, the norm and dip tests.
//! 4. A reference learned from the first readings may itself be a disturbance (a start
//!    next to a magnet). A different field that stays consistent while the sensor
//!    turns replaces a rejected reference (after 3 s when the reference was never seen
//!    while turning, else 20 s, as VQF's new-field acceptance); an attached magnet's
//!    field changes norm and dip as the sensor turns, so it never qualifies.
//!
//! Structure: `q = q_δ ⊗ (q_inc ⊗ q_gyr)` with `q_gyr` the bias-corrected strapdown (sensor
//! to I), `q_inc` the inclination correction (I to E′) and `q_δ` a rotation by δ about
//! the vertical (E′ to E, heading from the magnetometer). Native frame: ENU.
//!
//! Low-pass filters use the gain `dt / (τ + dt)` (backward Euler), which is stable for
//! any dt and needs no transcendental per sample.
//!
//! ## Heading uncertainty
//!
//! The filter reports one standard deviation of its heading error e (rad, about the
//! vertical, against its reference: magnetic north once the magnetometer was used, else
//! the start heading), propagated with the error of the vertical bias component b
//! (rad/s) as the 2×2 covariance `P = [[P_ee, P_eb], [P_eb, P_bb]]` of a linear error
//! model of this filter's own fixed-gain steps (orient's; this covariance drives nothing
//! but the report; the bias terms follow VQF's bias uncertainty and take its defaults,
//! which the motion bias filter shares, `motion_bias`). With
//! σ_g the gyroscope noise density (`gyro_noise`), σ_b the bias before any rest
//! (`bias_sigma`), σ_r the bias learned at rest (`bias_sigma_rest`), σ_w the bias random
//! walk (`bias_walk`), σ_s the scale and axis errors' heading error per √rad turned
//! (`gyro_scale_sigma`), σ_m the heading error of a clean accepted field
//! (`mag_heading_sigma`) and κ the heading error per unit of a field's deviation
//! (`mag_deviation_gain`):
//!
//! - (H1) gyroscope step of the angle θ = |ω − b̂| dt, e' = e + b dt + rate noise +
//!   scale error, b' = b + bias walk:
//!   `P_ee += 2 dt P_eb + dt² P_bb + σ_g² dt + σ_s² θ`, `P_eb += dt P_bb`,
//!   `P_bb = min(P_bb + σ_w² dt, σ_b²)` (|P_eb| then kept within √(P_ee P_bb)); from the
//!   start `P_ee = P_eb = 0` (the start heading is the reference), `P_bb = σ_b²`;
//! - (H2) bias step at rest with gain k_b (the bias's own, `bias_tau_rest`),
//!   b' = (1 - k_b) b + k_b ε with ε the rest estimate's error:
//!   `P_bb = (1 - k_b)² P_bb + k_b (2 - k_b) σ_r²`, `P_eb *= 1 - k_b`, so a rest brings
//!   the bias uncertainty to σ_r at any sample rate (the motion filter's covariance takes
//!   the same step on every axis); the bias learned in motion is not credited here (it
//!   sees the horizontal components only), so the uncertainty errs large;
//! - (H3) heading step with the gain k of an accepted field, e' = (1 - k) e + k v:
//!   `P_ee = (1 - k)² P_ee + k (2 - k) σ_v²`, `P_eb *= 1 - k`, with
//!   `σ_v² = σ_m² + κ² (Δ_n² + Δ_d²)`, Δ_n = |f| / n_ref − 1 and Δ_d = dip(f) − dip_ref the
//!   used field's deviation from the reference. A field the tests let through may still
//!   be disturbed (or the sensor badly calibrated, or the inclination off, which moves
//!   the measured dip): the part of a disturbance that turns the heading is not seen,
//!   but the parts that change the norm and the dip are, and they are its evidence. An
//!   accepted field's error lasts (a disturbance that passes the tests does not flip
//!   sign each sample), so v is counted with the variance that makes σ_v the floor at
//!   any sample rate, not as white noise that averaging would shrink: P_ee follows σ_v²
//!   with the time constant τ_mag / 2; the first field (k = 1) sets σ_v;
//! - (H4) no heading is more uncertain than one uniform on the circle: P_ee is capped at
//!   π²/3, and P_eb set to 0 when it is. A gap re-acquired without the magnetometer
//!   loses the gap's rotation, so P_ee is set to that cap; with it, to σ_m². A host's
//!   `set_quaternion` makes the heading exact (P_ee = P_eb = 0).
//!
//! - (H1′) a gyroscope reading faster than any MEMS part reports of real motion
//!   (`PLAUSIBLE_RATE`, 2000 °/s) is a glitch, not a rate: its whole turn θ may be
//!   heading error, `P_ee += θ²` (then (H4)'s cap);
//! - (H5) the innovation is evidence. With y = wrap(azimuth of the used field − δ) the
//!   heading innovation of an accepted field (the angle between the magnetometer's
//!   heading and the estimate's) and ȳ its low-pass (time constant τ_y), the model
//!   explains `E[ȳ²] ≲ P_ee + σ_v²`. A ȳ² beyond g² = 4 times that (a 2σ gate) is an
//!   error the model did not see (a host's wrong attitude, a gap integrated blind, a
//!   glitch below the plausible rate, a field that changed): the evidence
//!   `J' = max((1 − k) J, ȳ² if gated else 0)` keeps it, released at the correction's own
//!   gain k (the correction removes an estimate error e as (1 − k) per step, so J follows
//!   e² down no faster than e² falls), and the reported variance is
//!   `σ² = min(P_ee + c J, π²/3)`. J (and ȳ) are forgotten when the heading is set from
//!   outside the model (a host's `set_quaternion`, a re-acquisition, a far new
//!   reference); the first fields, averaged from the start heading, are no evidence. c = 1
//!   and τ_y = 4 s were chosen by leave-one-group-out cross-validation on BROAD (grid c
//!   0.25-1, τ_y 0.5-4 s, release τ_mag/2 to 10 τ_mag, gate 4-25: six of seven folds chose
//!   c = 1, τ_y = 4 s, release τ_mag, gate 4). On BROAD's motion the innovation is mostly
//!   the field's own error, which the gate leaves out: J changes the per-trial ratio little
//!   (0.59-1.69 held out) and lifts the 2σ coverage from 94.3 % to 95.4 %.
//!
//! What the evidence cannot see: a still sensor beside a magnet that passes the tests
//! turns the estimate to the wrong north, and once it has, the innovation is gone. J covers
//! the transition only (measured: 19° off, covered 22-27 % of the following 60 s). Holding
//! the evidence longer (release 10 τ_mag) would cover it for about 2 minutes, but BROAD's
//! trials with attached and stationary magnets then get a σ 5-10 times their error (ratio
//! 0.11-0.21), so it is not done: only the field's deviation (H3) speaks for such a magnet.
//!
//! While the magnetometer is distrusted only (H1) and (H2) act, so the uncertainty grows
//! (with the bias error as σ_b t, and with the angle turned); once it is trusted again
//! (H3) brings it back to about √(σ_v² + (σ τ_mag)² + σ_s² ω τ_mag / 2): the field's
//! error, the lag a bias error σ leaves behind a correction of time constant τ_mag (σ
//! being σ_r after a rest and σ_b without one), and the scale errors of turning at the
//! rate ω. A clean field at rest gives σ_m, a disturbed one or fast turning more.
//!
//! σ_m is the heading of a clean field at rest against an optically aligned north
//! (BROAD's trials: -1.5 to +1.3°); κ and σ_s were chosen by leave-one-group-out
//! cross-validation over BROAD's 14 shared trials (`tools/src/bin/robust_sigma.rs`;
//! docs/ACCURACY.md has the figures). The orientation does not depend on any of them.

use crate::filters::kinds::complementary::rotation_of;
use crate::filters::kinds::rest::{lp_gain, RestDetector, RestThresholds};
use crate::filters::params::settings;
use crate::filters::pipeline::estimator::Step;
use crate::filters::state::Codec;
use crate::math::{Quat, Vec3};

settings! {
    /// Settings of the recommended filter. Every default holds for hand-held and body-worn
    /// sensors at 50-1000 Hz; none is fitted to a single recording.
    pub struct RobustSettings {
        tau_acc: f64 = ROBUST_TAU_ACC 80 {
            unit: "s",
            default: 2.5,
            min: 1e-3,
            max: 1000.0,
            zero_off: false,
            doc: "Time constant of the accelerometer low-pass (2nd-order Butterworth, cutoff \
                 sqrt(2)/(2 pi tau)) in the quasi-inertial frame; default 2.5 (orient: long enough \
                 to average out hand and body accelerations; BROAD scores vary by under 0.03 deg \
                 over 2.5-3 s).",
        },
        tau_mag: f64 = ROBUST_TAU_MAG 81 {
            unit: "s",
            default: 9.0,
            min: 1e-3,
            max: 1000.0,
            zero_off: false,
            doc: "Time constant of the magnetometer heading correction; default 9 (VQF's default: \
                 slow enough that a short undetected disturbance moves heading little).",
        },
        rest_gyro: f64 = ROBUST_REST_GYRO 82 {
            unit: "rad/s",
            default: 0.03490658503988659,
            min: 0.0,
            max: 10.0,
            zero_off: false,
            doc: "Rest when the gyroscope's spread around its low-pass and the low-pass itself stay \
                 below this; default 0.0349 (2 deg/s, VQF's default; MEMS biases are below it); \
                 another under joints (orient_config_for_joints()), with bias_limit.",
        },
        rest_accel: f64 = ROBUST_REST_ACCEL 83 {
            unit: "m/s^2",
            default: 0.5,
            min: 0.0,
            max: 100.0,
            zero_off: false,
            doc: "Rest when the accelerometer's spread around its low-pass stays below this; \
                 default 0.5 (VQF's default).",
        },
        rest_time: f64 = ROBUST_REST_TIME 84 {
            unit: "s",
            default: 1.5,
            min: 0.0,
            max: 3600.0,
            zero_off: false,
            doc: "How long the rest conditions must hold before the sensor counts as resting (0: \
                 rest_tau/2, the tilt test's window, rest_tilt); default 1.5 (VQF's default).",
        },
        rest_tilt: f64 = ROBUST_REST_TILT 92 {
            unit: "rad",
            default: 0.008726646259971648,
            min: 0.0,
            max: 3.2,
            zero_off: false,
            doc: "Rest also needs the accelerometer's direction to stay within this angle of where \
                 the still period began (the mean of its first window of rest_tau/2, or \
                 rest_time/6 when shorter, against a low-pass of that window started with the \
                 period), so a slow turn under rest_gyro is not learned as bias; default 0.0087 \
                 (0.5 deg, orient: 10x the direction noise after the rest low-pass of a consumer \
                 MEMS accelerometer).",
        },
        rest_tau: f64 = ROBUST_REST_TAU 85 {
            unit: "s",
            default: 0.5,
            min: 1e-3,
            max: 100.0,
            zero_off: false,
            doc: "Time constant of the low-pass that rest detection compares against (the tilt \
                 test, rest_tilt, takes half of it, or rest_time/6 when shorter); default 0.5 \
                 (VQF's default).",
        },
        bias_tau_rest: f64 = ROBUST_BIAS_TAU_REST 86 {
            unit: "s",
            default: 1.0,
            min: 1e-3,
            max: 3600.0,
            zero_off: false,
            doc: "Time constant with which the bias follows the low-passed gyroscope at rest; \
                 default 1 (orient: a hand's pauses last a few seconds, of which rest detection \
                 takes rest_time; shorter learns more of each pause but also more of a slow turn \
                 that starts from rest below rest_gyro, docs/ACCURACY.md).",
        },
        bias_sigma_motion: f64 = ROBUST_BIAS_SIGMA_MOTION 100 {
            unit: "rad/s",
            default: 0.000_523_598_775_598_298_8,
            min: 0.0,
            max: 1.0,
            zero_off: true,
            doc: "Standard deviation the bias estimate in motion settles to while the inclination \
                 correction measures the bias (sigma_m of the motion bias Kalman filter, VQF's \
                 biasSigmaMotion; smaller learns faster and trusts the correction more); default \
                 5.24e-4 (0.03 deg/s, orient: with the filter's rate and acceleration terms, \
                 chosen on BROAD and simulated gloves, docs/ACCURACY.md); 0 turns the estimate \
                 in motion off.",
        },
        bias_limit: f64 = ROBUST_BIAS_LIMIT 88 {
            unit: "rad/s",
            default: 0.03490658503988659,
            min: 0.0,
            max: 10.0,
            zero_off: false,
            doc: "Largest component the motion estimate may give the bias, and its measurement \
                 error (a larger component learned at rest raises the bound for every component \
                 to it); default 0.0349 (orient: 2 deg/s, VQF's biasClip and the rest threshold: \
                 a larger bias would also hide rest); another under joints, with rest_gyro \
                 (orient_config_for_joints()).",
        },
        mag_norm_th: f64 = ROBUST_MAG_NORM_TH 89 {
            unit: "1",
            default: 0.1,
            min: 0.0,
            max: 10.0,
            zero_off: false,
            doc: "Magnetic disturbance when the field norm deviates from the reference by more \
                 than this fraction; default 0.1 (VQF's default).",
        },
        mag_dip_th: f64 = ROBUST_MAG_DIP_TH 90 {
            unit: "rad",
            default: 0.17453292519943295,
            min: 0.0,
            max: 3.2,
            zero_off: false,
            doc: "Magnetic disturbance when the dip angle deviates from the reference by more than \
                 this; default 0.1745 (10 deg, VQF's default).",
        },
        hard_iron_time: f64 = ROBUST_HARD_IRON_TIME 91 {
            unit: "s",
            default: 3.0,
            min: 1e-3,
            max: 3600.0,
            zero_off: true,
            doc: "A sensor-fixed disturbance (attached magnet) is compensated once its estimate has \
                 been consistent this long; default 3 (orient); 0 turns compensation off.",
        },
        gyro_noise: f64 = ROBUST_GYRO_NOISE 93 {
            unit: "rad/s/sqrt(Hz)",
            default: 1.7453292519943296e-4,
            min: 0.0,
            max: 1.0,
            zero_off: false,
            doc: "Gyroscope rate noise density, for the heading uncertainty only (eq. H1); default \
                 1.745e-4 (orient: 0.01 deg/s/sqrt(Hz), the MPU-9250 datasheet's, the largest of common \
                 MEMS gyroscopes: BMI270 0.007, LSM6DSO 0.0038).",
        },
        bias_sigma: f64 = ROBUST_BIAS_SIGMA 94 {
            unit: "rad/s",
            default: 0.008726646259971648,
            min: 0.0,
            max: 10.0,
            zero_off: false,
            doc: "Standard deviation of the gyroscope bias before any rest, and the most its \
                 uncertainty grows back to: the heading uncertainty's (eq. H1) and the motion \
                 bias filter's starting and largest covariance (0 leaves that filter nothing to \
                 learn); default 0.0087 (0.5 deg/s: VQF's biasSigmaInit, and the typical \
                 zero-rate offset after soldering in the BMI270 and LSM6DSO datasheets).",
        },
        bias_sigma_rest: f64 = ROBUST_BIAS_SIGMA_REST 95 {
            unit: "rad/s",
            default: 5.235987755982989e-4,
            min: 0.0,
            max: 10.0,
            zero_off: false,
            doc: "Standard deviation of the bias learned at rest: what the bias uncertainty settles \
                 to during a rest, the heading uncertainty's (eq. H2) and the motion bias \
                 filter's covariance; default 5.24e-4 (0.03 deg/s, VQF's biasSigmaRest).",
        },
        bias_walk: f64 = ROBUST_BIAS_WALK 96 {
            unit: "rad/s/sqrt(s)",
            default: 1.7453292519943296e-4,
            min: 0.0,
            max: 10.0,
            zero_off: false,
            doc: "Random walk of the gyroscope bias: how fast the motion bias filter lets a \
                 learned bias go (its process noise) and the heading uncertainty grows with it \
                 (eq. H1); larger follows a drifting bias sooner and takes more of a fast motion's \
                 scale errors for bias; 0 learns the bias at rest only; default 1.745e-4 (0.01 \
                 deg/s/sqrt(s): VQF's 0.1 deg/s over its biasForgettingTime of 100 s); another under \
                 joints (orient_config_for_joints()).",
        },
        mag_heading_sigma: f64 = ROBUST_MAG_HEADING_SIGMA 97 {
            unit: "rad",
            default: 0.017453292519943295,
            min: 0.0,
            max: 1.8,
            zero_off: false,
            doc: "Standard deviation of the heading a clean accepted magnetometer field gives, for \
                 the heading uncertainty only (eq. H3): the floor the uncertainty settles to while \
                 an undisturbed field is used; at most 1.8, the sigma of a heading uniform on the \
                 circle (eq. H4); default 0.01745 (1 deg, orient: the heading of a clean field at \
                 rest against BROAD's optically aligned north, -1.5 to +1.3 deg over its trials).",
        },
        mag_deviation_gain: f64 = ROBUST_MAG_DEVIATION_GAIN 98 {
            unit: "1",
            default: 0.2,
            min: 0.0,
            max: 100.0,
            zero_off: false,
            doc: "Heading error per unit of an accepted field's deviation from the reference (its \
                 dip's in rad and its norm's as a fraction), for the heading uncertainty only (eq. \
                 H3): a field the norm and dip tests let through still turns the heading; default 0.2 \
                 (orient: chosen by leave-one-group-out cross-validation over BROAD's 14 shared \
                 trials, tools/src/bin/robust_sigma.rs: 0.1 or 0.2 in every fold).",
        },
        gyro_scale_sigma: f64 = ROBUST_GYRO_SCALE_SIGMA 99 {
            unit: "sqrt(rad)",
            default: 0.0075,
            min: 0.0,
            max: 1.0,
            zero_off: false,
            doc: "Heading error the gyroscope's scale and axis errors add per square root of the \
                 angle turned, for the heading uncertainty only (eq. H1); default 0.0075 (orient: \
                 chosen by leave-one-group-out cross-validation over BROAD's 14 shared trials, \
                 tools/src/bin/robust_sigma.rs: 0.0075 in every fold).",
        },
    }
}

/// The recommended filter. See the module documentation.
#[derive(Clone, Debug, PartialEq)]
pub struct Robust {
    pub settings: RobustSettings,
    /// Strapdown orientation, sensor to quasi-inertial frame.
    q_gyr: Quat,
    /// Inclination correction, quasi-inertial frame to E′.
    q_inc: Quat,
    /// Heading correction about the vertical, `q_δ`.
    turn: Turn,
    /// The output, `q_δ ⊗ q_inc ⊗ q_gyr`.
    q: Quat,
    bias: Vec3,
    /// Second-order Butterworth low-pass of the accelerometer in the quasi-inertial frame.
    acc_lp: Butterworth,
    acc_seen: bool,
    rest: RestDetector,
    /// Magnetic reference: norm and dip; `mag_count` undisturbed samples used so far.
    ref_norm: f64,
    ref_dip: f64,
    mag_count: u32,
    mag_disturbed: bool,
    /// Hard iron: running estimate, its spread, how long it has been consistent, and
    /// the offset in use (when `hard_iron_on`).
    hi_lp: Vec3,
    hi_spread: f64,
    hi_clock: f64,
    hi_started: bool,
    hard_iron: Vec3,
    hard_iron_on: bool,
    /// Seconds the reference field has been seen, accepted, while the sensor turned (up
    /// to [`MAG_CONFIRM_TIME`]): a field seen only at rest may be a magnet's.
    ref_confirmed: f64,
    /// A candidate for a new reference: the low-passed norm and dip of the readings, and
    /// how long they have stayed consistent while the sensor turned.
    cand_norm: f64,
    cand_dip: f64,
    cand_clock: f64,
    /// The heading uncertainty (module documentation, (H1)-(H4)).
    heading_var: HeadingVariance,
    /// The bias filter in motion ([`motion_bias`]).
    motion: MotionBias,
}

impl Robust {
    pub fn new(settings: RobustSettings) -> Robust {
        Robust {
            heading_var: HeadingVariance::start(&settings),
            motion: MotionBias::new(settings.bias_sigma),
            settings,
            q_gyr: Quat::IDENTITY,
            q_inc: Quat::IDENTITY,
            turn: Turn::IDENTITY,
            q: Quat::IDENTITY,
            bias: Vec3::ZERO,
            acc_lp: Butterworth::default(),
            acc_seen: false,
            rest: RestDetector::default(),
            ref_norm: 0.0,
            ref_dip: 0.0,
            mag_count: 0,
            mag_disturbed: false,
            hi_lp: Vec3::ZERO,
            hi_spread: 0.0,
            hi_clock: 0.0,
            hi_started: false,
            hard_iron: Vec3::ZERO,
            hard_iron_on: false,
            ref_confirmed: 0.0,
            cand_norm: 0.0,
            cand_dip: 0.0,
            cand_clock: 0.0,
        }
    }

    pub fn quaternion(&self) -> Quat {
        self.q
    }

    /// Sets the orientation; the bias, rest state and magnetic reference are kept.
    pub fn set_quaternion(&mut self, q: Quat) {
        self.q_gyr = q;
        self.q_inc = Quat::IDENTITY;
        self.turn = Turn::IDENTITY;
        self.q = q;
        self.acc_seen = false;
        self.heading_var.p_ee = 0.0;
        self.heading_var.p_eb = 0.0;
        self.heading_var.forget_innovation();
    }

    pub fn bias(&self) -> Vec3 {
        self.bias
    }

    /// After a gap: inclination from this accelerometer reading, heading from the
    /// magnetometer only when its field (less the hard iron in use) passes the norm and
    /// dip tests against the reference, else the heading held; the low-passes, rest
    /// detection and the hard-iron consistency clock start over; the bias (but for the
    /// rest watch's still reading, which becomes it), the magnetic reference and a
    /// hard-iron offset in use are kept.
    pub(crate) fn reacquire(&mut self, r: &crate::filters::pipeline::estimator::Reacquisition) -> bool {
        if let Some(g) = r.still {
            self.bias = g;
        }
        let mut q = r.keep;
        let mut used_mag = false;
        if let Some(m) = r.mag {
            let m = if self.hard_iron_on { m - self.hard_iron } else { m };
            let trusted = self.mag_count == 0 || self.accepts(r.keep.rotate(m));
            if let Some(with_mag) =
                crate::math::Frame::Enu.attitude_from(r.accel, Some(m)).filter(|_| trusted)
            {
                q = with_mag;
                used_mag = true;
            }
        }
        self.q_gyr = q;
        self.q_inc = Quat::IDENTITY;
        self.turn = Turn::IDENTITY;
        self.q = q;
        self.acc_lp.start(q.rotate(r.accel));
        self.motion.start(q, self.bias);
        self.acc_seen = true;
        self.rest = RestDetector::default();
        self.hi_started = false;
        self.hi_clock = 0.0;
        self.mag_disturbed = !used_mag && r.mag.is_some();
        if used_mag {
            self.heading_var.heading_step(1.0, self.settings.mag_heading_sigma);
            self.heading_var.forget_innovation();
        } else {
            self.heading_var.lost();
        }
        used_mag
    }

    /// One standard deviation of the heading error (rad; module documentation,
    /// (H1)-(H4)).
    pub fn heading_sigma(&self) -> f64 {
        self.heading_var.reported().sqrt()
    }

    /// True when the last sample was classified as rest.
    pub fn at_rest(&self) -> bool {
        self.rest.at_rest()
    }

    /// True when the last magnetometer reading was rejected as disturbed.
    pub fn mag_disturbed(&self) -> bool {
        self.mag_disturbed
    }

    /// The hard-iron offset being subtracted from the magnetometer, if any.
    pub fn hard_iron(&self) -> Option<Vec3> {
        self.hard_iron_on.then_some(self.hard_iron)
    }

    /// Values an update could leave (see `filters::holds`).
    pub(crate) fn valid(&self) -> bool {
        use crate::filters::state::holds;
        use core::f64::consts::PI;
        holds::unit(self.q_gyr)
            && holds::unit(self.q_inc)
            && holds::unit_product_of_three(self.q)
            && self.turn.valid()
            && holds::rate(self.bias)
            && self.acc_lp.valid()
            && self.rest.valid()
            && holds::mag_norm(self.ref_norm)
            && holds::within(self.ref_dip, -PI, PI)
            && holds::mag(self.hi_lp)
            && holds::mag_spread(self.hi_spread)
            && self.hi_clock >= 0.0
            && holds::mag(self.hard_iron)
            && holds::within(self.ref_confirmed, 0.0, MAG_CONFIRM_TIME)
            && holds::mag_norm(self.cand_norm)
            && holds::within(self.cand_dip, -PI, PI)
            && self.cand_clock >= 0.0
            && self.heading_var.valid()
            && self.motion.valid()
    }

    pub(crate) fn codec(&mut self, c: &mut dyn Codec) {
        c.quat(&mut self.q_gyr);
        c.quat(&mut self.q_inc);
        c.f64(&mut self.turn.c);
        c.f64(&mut self.turn.s);
        c.quat(&mut self.q);
        c.vec3(&mut self.bias);
        self.acc_lp.codec(c);
        c.bool(&mut self.acc_seen);
        self.rest.codec(c);
        c.f64(&mut self.ref_norm);
        c.f64(&mut self.ref_dip);
        c.u32(&mut self.mag_count);
        c.bool(&mut self.mag_disturbed);
        c.vec3(&mut self.hi_lp);
        c.f64(&mut self.hi_spread);
        c.f64(&mut self.hi_clock);
        c.bool(&mut self.hi_started);
        c.vec3(&mut self.hard_iron);
        c.bool(&mut self.hard_iron_on);
        c.f64(&mut self.ref_confirmed);
        c.f64(&mut self.cand_norm);
        c.f64(&mut self.cand_dip);
        c.f64(&mut self.cand_clock);
        self.heading_var.codec(c);
        self.motion.codec(c);
    }

    /// One step, in place: `None` when it left the orientation non-finite, which no sample
    /// the filter's runner accepts can cause (the argument follows). Then the filter
    /// starts over from the orientation it had before the step, keeping its settings and
    /// a finite bias (`Robust::restart`). The orientation is the one value checked: a
    /// non-finite bias or δ reaches it by the next step, the heading covariance's (H4)
    /// sets a NaN or infinite variance back to the lost heading's, the hard-iron estimate
    /// starts over from a non-finite value, and a non-finite magnetic reference or
    /// candidate is replaced by the next reading that is not. It dispatches on the
    /// magnetometer reading to two out-of-line copies of that guarded step
    /// (`update_without_mag`, `update_with_mag`), each compiled for its own path; out of
    /// line for the reason given at `Complementary::update`.
    ///
    /// No copy of the state is kept to put back: the copy was the largest single cost of
    /// the update (docs/PERFORMANCE.md). It is not needed, because from any state
    /// `Robust::valid` accepts, with settings in their ranges, and a sample within the
    /// runner's bounds (dt in [1e-9, 1e6] s; each component under 1e4 rad/s, 1e5 m/s²
    /// and 1e12, and the accelerometer's and magnetometer's squared norms at least
    /// `f64::MIN_POSITIVE`), every value the step stores is finite:
    /// - Every low-pass (rest detector, bias at rest, magnetic reference and candidate,
    ///   hard iron) moves by a gain in [0, 1] (`dt / (τ + dt)`, or a mean's `dt / t` with
    ///   t ≥ dt the time it has averaged) towards a bounded input:
    ///   it stays between its old value and its input. The Butterworth low-pass is the
    ///   exact flow of a stable system (its coefficients have |·| ≤ √2 max(1, τ, 2/τ)),
    ///   so its state stays within a constant factor of its inputs and its own bound.
    /// - Products are bounded by the readings' bounds: the largest squares are the
    ///   magnetometer's, below 1e30 (the hard-iron spread of a field 10 times the bound);
    ///   `dt² P_bb` is below 1e12 · 1e10.
    /// - Every division and normalisation has a divisor bounded away from zero:
    ///   quaternions are products of unit ones (so their squared norms, near 1, are in
    ///   `inv_sqrt`'s fast range, and are normalised without its range test); the
    ///   accelerometer's earth vector is tested (`1e-12`); the low-pass gains divide by
    ///   τ + dt > 0; the heading error divides x′ by y′ only when y′ > 4|x′| (a quotient
    ///   under 1/4); a magnetometer reading's rotated norm is its own (nonzero) norm to
    ///   rounding, and a difference of fields that vanishes gives a NaN dip that fails
    ///   every comparison and is never stored.
    /// - The motion bias filter (`motion_bias`) divides σ_m⁴ by its V only when V > 0, and
    ///   may compute an infinite or NaN value from low-passes at the ends of their range
    ///   (its 1/det, its products) or from a V so small that σ_m⁴ / V overflows: it stores its
    ///   update only when the bias and the covariance come out finite, and clips the bias
    ///   to its bound.
    /// - Angles: `sin`/`cos` of any finite argument (|ω| dt up to 2e11 rad) are finite;
    ///   `asin` sees a clamped argument, `atan2` finite ones.
    /// - Clocks grow by dt at most per step and saturate in floating point before
    ///   overflowing.
    ///
    /// A step from a state at the very ends of `valid`'s bounds may leave one a little
    /// beyond them (the low-pass's output up to about 3e14 from a rate of 1e12); the
    /// argument holds the same from there, every bound being as far from overflow. The
    /// filter's own states from bounded readings stay well inside. The reference norm is
    /// held within `holds::MAG_NORM_MAX`: a compensated field may be larger than any
    /// reading (`a_large_compensated_field_keeps_the_reference_valid`).
    ///
    /// A randomised test (`no_accepted_sample_makes_the_step_non_finite`) steps forged
    /// states at their bounds with samples at theirs and settings at their range ends.
    #[inline(always)]
    pub fn update(&mut self, dt: f64, gyro: Vec3, accel: Option<Vec3>, mag: Option<Vec3>) -> Option<Step> {
        match mag {
            None => self.update_without_mag(dt, gyro, accel),
            Some(m) => self.update_with_mag(dt, gyro, accel, m),
        }
    }

    /// [`Robust::update`] without a magnetometer reading: one out-of-line copy per case,
    /// each compiled for its own path.
    #[inline(never)]
    fn update_without_mag(&mut self, dt: f64, gyro: Vec3, accel: Option<Vec3>) -> Option<Step> {
        self.guarded(dt, gyro, accel, None)
    }

    /// [`Robust::update`] with a magnetometer reading.
    #[inline(never)]
    fn update_with_mag(&mut self, dt: f64, gyro: Vec3, accel: Option<Vec3>, mag: Vec3) -> Option<Step> {
        self.guarded(dt, gyro, accel, Some(mag))
    }

    #[inline(always)]
    fn guarded(&mut self, dt: f64, gyro: Vec3, accel: Option<Vec3>, mag: Option<Vec3>) -> Option<Step> {
        let q = self.q;
        let step = self.step(dt, gyro, accel, mag);
        if !self.q.is_finite() {
            self.restart(q);
            return None;
        }
        Some(step)
    }

    /// The guard's answer to a non-finite step (see [`Robust::update`]; only readings
    /// outside the runner's bounds reach it): the orientation `q` from before the step, the
    /// settings and a finite bias are kept; the rest starts as new, with the heading
    /// uncertainty that of a lost heading (H4), so good samples bring the filter back.
    #[cold]
    #[inline(never)]
    fn restart(&mut self, q: Quat) {
        let bias = if self.bias.is_finite() { self.bias } else { Vec3::ZERO };
        *self = Robust { bias, ..Robust::new(self.settings) };
        self.set_quaternion(q);
        self.heading_var.lost();
    }

    #[inline(always)]
    fn step(&mut self, dt: f64, gyro: Vec3, accel: Option<Vec3>, mag: Option<Vec3>) -> Step {
        let s = &self.settings;
        let mut step = Step::default();
        let th = RestThresholds {
            gyro: s.rest_gyro,
            accel: s.rest_accel,
            tilt: s.rest_tilt,
            time: s.rest_time,
            tau: s.rest_tau,
        };
        if self.rest.update_with_bias(dt, gyro, self.bias, accel, &th) {
            let k_b = lp_gain(dt, s.bias_tau_rest);
            self.bias = self.bias + (self.rest.gyro_lp() - self.bias) * k_b;
            self.heading_var.bias_step(k_b, s.bias_sigma_rest);
            self.motion.rest_step(k_b, s.bias_sigma_rest);
        }
        self.q_gyr = (self.q_gyr * rotation_of(gyro - self.bias, dt)).normalized_in_range();
        self.heading_var.gyro_step(dt, (gyro - self.bias).norm() * dt, s);
        if let Some(a) = accel {
            step.used_accel = true;
            self.correct_inclination(dt, a, (gyro - self.bias).norm_squared());
        } else {
            // The next correction removes this sample's drift too: its time counts.
            self.motion.elapse(dt, (gyro - self.bias).norm_squared());
        }
        // E′: the sensor to the inclination-corrected frame, for the heading correction
        // and the output.
        let q_e = self.q_inc * self.q_gyr;
        if let Some(m) = mag {
            step.used_mag = self.correct_heading(dt, m, q_e);
        }
        // q = q_δ ⊗ q_e. Without a heading offset (every update without a magnetometer)
        // q_δ is the identity, and no product is needed. q is computed again from its
        // three factors at every step and not normalised: each factor is unit to
        // rounding when the filter's own steps made it (q_gyr is normalised at every
        // step, q_inc at every accelerometer reading, q_δ at every heading correction),
        // and within `holds::unit`'s 1e-9 when a snapshot loaded it, so q is unit to a
        // few ulp, or within 3e-9 (`holds::unit_product_of_three`, what `valid` checks).
        self.q = if self.turn == Turn::IDENTITY { q_e } else { self.turn.times(q_e) };
        step
    }
}

mod field;
mod hard_iron;
mod heading;
mod inclination;
mod motion_bias;
use field::*;
use heading::*;
use inclination::*;
use motion_bias::MotionBias;

#[cfg(test)]
mod tests;

/// The common lifecycle's view of this kind (see [`crate::filters::pipeline::estimator::Estimator`]).
mod estimator_impl {
    use super::*;
    use crate::filters::pipeline::estimator::estimator;
    use crate::filters::Diagnostics;

    estimator!(impl for Robust { settings: RobustSettings, native: Enu, own_startup: false, diagnostics: GYRO_BIAS | REST } {
        const FAILURE_RESTARTS: bool = true;

        #[inline(always)]
        fn update(&mut self, dt: f64, gyro: Vec3, accel: Option<Vec3>, mag: Option<Vec3>) -> Option<Step> {
            Robust::update(self, dt, gyro, accel, mag)
        }

        fn diagnose(&self, d: &mut Diagnostics) {
            d.gyro_bias = self.bias();
            d.rest = if self.at_rest() { 1.0 } else { 0.0 };
        }

        fn at_rest(&self) -> bool {
            Robust::at_rest(self)
        }

        fn uncertainty(&self) -> crate::filters::Uncertainty {
            crate::filters::Uncertainty { heading: Some(self.heading_sigma()), inclination: None }
        }

        fn configure(&mut self, settings: RobustSettings) {
            self.heading_var.configure(&self.settings, &settings);
            self.settings = settings;
        }

        fn mag_disturbed(&self) -> bool {
            Robust::mag_disturbed(self)
        }

        fn learns_bias_in_motion(&self) -> bool {
            // The motion bias filter: bias_sigma_motion 0 turns it off, a bias_walk of 0
            // learns at rest only and a bias_sigma of 0 leaves it nothing to learn.
            let s = &self.settings;
            s.bias_sigma_motion > 0.0 && s.bias_walk > 0.0 && s.bias_sigma > 0.0
        }
    });
}
