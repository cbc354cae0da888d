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
//!    filter keeps applying is the drift a bias error causes: a slow integral of it,
//!    mapped back into the sensor frame, estimates the bias components that tilt the
//!    estimate (the vertical one is unobservable from gravity).
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
//! model of this filter's own fixed-gain steps (orient's; no covariance drives the
//! estimate; the bias terms follow VQF's bias uncertainty and take its defaults). With
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
//!   the bias uncertainty to σ_r at any sample rate; the bias learned in motion is not
//!   credited (it sees the horizontal components only), so the uncertainty errs large;
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

use super::complementary::rotation_of;
use super::params::settings;
use super::rest::{lp_gain, RestDetector, RestThresholds};
use super::state::Codec;
use super::Step;
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
                 below this; default 0.0349 (2 deg/s, VQF's default; MEMS biases are below it).",
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
            doc: "How long the rest conditions must hold before the sensor counts as resting; \
                 default 1.5 (VQF's default).",
        },
        rest_tilt: f64 = ROBUST_REST_TILT 92 {
            unit: "rad",
            default: 0.008726646259971648,
            min: 0.0,
            max: 3.2,
            zero_off: false,
            doc: "Rest also needs the low-passed accelerometer direction to stay within this angle \
                 of where the still period began, so a slow turn under rest_gyro is not learned \
                 as bias; default 0.0087 (0.5 deg, orient: 10x the direction noise after the \
                 rest low-pass of a consumer MEMS accelerometer).",
        },
        rest_tau: f64 = ROBUST_REST_TAU 85 {
            unit: "s",
            default: 0.5,
            min: 1e-3,
            max: 100.0,
            zero_off: false,
            doc: "Time constant of the low-pass that rest detection compares against; default 0.5 \
                 (VQF's default).",
        },
        bias_tau_rest: f64 = ROBUST_BIAS_TAU_REST 86 {
            unit: "s",
            default: 2.0,
            min: 1e-3,
            max: 3600.0,
            zero_off: false,
            doc: "Time constant with which the bias follows the low-passed gyroscope at rest; \
                 default 2 (orient: settles within a typical 5-10 s pause).",
        },
        bias_tau_motion: f64 = ROBUST_BIAS_TAU_MOTION 87 {
            unit: "s",
            default: 100.0,
            min: 1e-3,
            max: 1e6,
            zero_off: true,
            doc: "Time constant of the bias estimate from the accelerometer correction in motion; \
                 default 100 (orient: 40 times tau_acc, so accelerations that leak through the \
                 low-pass average out before they move the bias); 0 turns it off.",
        },
        bias_limit: f64 = ROBUST_BIAS_LIMIT 88 {
            unit: "rad/s",
            default: 0.03490658503988659,
            min: 0.0,
            max: 10.0,
            zero_off: false,
            doc: "Largest bias norm the motion estimate may reach; default 0.0349 (orient: 2 deg/s, \
                 the rest threshold: a larger bias would also hide rest).",
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
                 uncertainty grows back to, for the heading uncertainty only (eq. H1); default \
                 0.0087 (0.5 deg/s: VQF's biasSigmaInit, and the typical zero-rate offset after \
                 soldering in the BMI270 and LSM6DSO datasheets).",
        },
        bias_sigma_rest: f64 = ROBUST_BIAS_SIGMA_REST 95 {
            unit: "rad/s",
            default: 5.235987755982989e-4,
            min: 0.0,
            max: 10.0,
            zero_off: false,
            doc: "Standard deviation of the bias learned at rest, for the heading uncertainty only \
                 (eq. H2): what the bias uncertainty settles to during a rest; default 5.24e-4 \
                 (0.03 deg/s, VQF's biasSigmaRest).",
        },
        bias_walk: f64 = ROBUST_BIAS_WALK 96 {
            unit: "rad/s/sqrt(s)",
            default: 1.7453292519943296e-4,
            min: 0.0,
            max: 10.0,
            zero_off: false,
            doc: "Random walk of the gyroscope bias, for the heading uncertainty only (eq. H1): a \
                 bias learned at rest is forgotten at this rate; default 1.745e-4 (0.01 deg/s/sqrt(s): \
                 VQF's 0.1 deg/s over its biasForgettingTime of 100 s).",
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

/// Dip of an earth-frame (ENU) field: positive when it points down.
fn dip(f: Vec3) -> f64 {
    libm::asin((-f.z / f.norm()).clamp(-1.0, 1.0))
}

/// `(E C, E S)` with `E = exp(−x)`, `C = cos x`, `S = sin x`: the readable form, with libm
/// (beyond the series' range, and what the series is tested against).
#[cold]
#[inline(never)]
fn exp_turn(x: f64) -> (f64, f64) {
    let e = libm::exp(-x);
    let (s, c) = libm::sincos(x);
    (e * c, e * s)
}

/// [`exp_turn`] for `0 ≤ x < 1/32` by the series of `exp((−1 + i) x) = Σ (−1 + i)ⁿ xⁿ / n!`
/// (real part `E C`, imaginary part `E S`) through x⁹: the first term left out is below
/// 2⁻⁶⁰ of the sum there. `None` beyond. dt jitters on every host, so the coefficients
/// are recomputed at nearly every step; the series costs the robust update fewer
/// instructions than libm's `exp` and `sincos` (docs/PERFORMANCE.md).
#[inline(always)]
fn exp_turn_series(x: f64) -> Option<(f64, f64)> {
    if !(0.0..1.0 / 32.0).contains(&x) {
        return None;
    }
    // Real parts of (−1 + i)ⁿ / n!: 1, −1, 0, 1/3, −1/6, 1/30, 0, −1/630, 1/2520, −1/22680.
    let ec = 1.0
        + x * (-1.0
            + x * x
                * (1.0 / 3.0
                    + x * (-1.0 / 6.0
                        + x * (1.0 / 30.0
                            + x * x * (-1.0 / 630.0 + x * (1.0 / 2520.0 + x * (-1.0 / 22680.0)))))));
    // Imaginary parts: 0, 1, −1, 1/3, 0, −1/30, 1/90, −1/630, 0, 1/22680.
    let es = x
        * (1.0
            + x * (-1.0
                + x * (1.0 / 3.0
                    + x * x
                        * (-1.0 / 30.0 + x * (1.0 / 90.0 + x * (-1.0 / 630.0 + x * x * (1.0 / 22680.0)))))));
    Some((ec, es))
}

/// A second-order Butterworth low-pass of a vector, `ÿ = ω² (x − y) − 2ζω ẏ` with
/// ζ = 1/√2 and ω = √2/τ (cutoff `√2 / (2π τ)` for time constant τ), stepped exactly
/// for an input held over each step (x is the sample that ends it). With the deviation
/// `e = y − x` and the damped frequency `ω_d = ω √(1 − ζ²) = 1/τ`, one step of dt is
///
/// ```text
/// e' = E [(C + S) e + τ S ẏ],   ẏ' = E [−(2/τ) S e + (C − S) ẏ],
/// E = exp(−dt/τ), C = cos(dt/τ), S = sin(dt/τ)
/// ```
///
/// (the flow of the equation over dt). Two properties make it safe for any dt and any
/// sequence of dt, where the usual biquad is not:
/// - The state is the output and its rate in physical units, so a step of another dt (a
///   late packet, a gap) meets a state that means the same at every dt. A biquad's
///   state holds differences per sample, which a longer step misreads as a rate many
///   times too large and answers with a swing of degrees.
/// - Each step is the equation's own flow, so the filter stays stable for every dt and
///   the output settles on the input when dt is long against τ. A bilinear step would
///   ring at the Nyquist frequency there, and a pre-warped one turns unstable once
///   `ω dt / 2` reaches π/2.
///
/// The coefficients are recomputed only when dt or τ change.
#[derive(Clone, Debug, Default, PartialEq)]
struct Butterworth {
    /// dt and τ the coefficients belong to.
    dt: f64,
    tau: f64,
    /// One step: `e' = ee·e + ev·ẏ`, `ẏ' = ve·e + vv·ẏ`.
    ee: f64,
    ev: f64,
    ve: f64,
    vv: f64,
    /// Output y and its rate ẏ (per second).
    y: Vec3,
    v: Vec3,
    /// Started with [`Butterworth::start`] and still within the first τ: the output is
    /// the time-weighted mean of the inputs so far (`mean_t` seconds of them).
    warming: bool,
    mean_t: f64,
}

impl Butterworth {
    fn coefficients(&mut self, dt: f64, tau: f64) {
        if dt == self.dt && tau == self.tau {
            return;
        }
        // E C and E S, the real and imaginary parts of exp((−1 + i) x) with x = dt/τ.
        let (ec, es) = exp_turn_series(dt / tau).unwrap_or_else(|| exp_turn(dt / tau));
        self.ee = ec + es;
        self.ev = es * tau;
        self.ve = -2.0 * es / tau;
        self.vv = ec - es;
        self.dt = dt;
        self.tau = tau;
    }

    /// Coefficients that belong to their dt and τ (or none yet) and a bounded state.
    fn valid(&self) -> bool {
        let mut fresh = Butterworth { dt: f64::NAN, ..self.clone() };
        let coefficients = if self.dt == 0.0 && self.tau == 0.0 {
            [self.ee, self.ev, self.ve, self.vv] == [0.0; 4]
        } else {
            fresh.coefficients(self.dt, self.tau);
            // Within 1e-14, not bit for bit: snapshots written before the series
            // (`exp_turn_series`) hold libm's coefficients, a few units of 2⁻⁵² away.
            let close = |a: f64, b: f64| (a - b).abs() <= 1e-14 * b.abs();
            self.dt > 0.0
                && self.tau > 0.0
                && close(self.ee, fresh.ee)
                && close(self.ev, fresh.ev)
                && close(self.ve, fresh.ve)
                && close(self.vv, fresh.vv)
        };
        coefficients && super::holds::accel(self.y) && self.v.max_abs() < 1e12 && self.mean_t >= 0.0
    }

    /// Sets the state to the steady state of a constant input `x`.
    fn settle(&mut self, x: Vec3) {
        self.y = x;
        self.v = Vec3::ZERO;
        self.warming = false;
    }

    /// Starts from one reading: for the first τ the output is the mean of the readings
    /// so far, then the filter runs from that mean at rest. One reading taken in motion
    /// (a linear acceleration, a vibration) would otherwise stay in the output for
    /// several τ; the mean forgets it as 1/n. (VQF starts its low-passes the same way.)
    fn start(&mut self, x: Vec3) {
        self.settle(x);
        self.warming = true;
        self.mean_t = 0.0;
    }

    fn filter(&mut self, dt: f64, tau: f64, x: Vec3) -> Vec3 {
        self.coefficients(dt, tau);
        if self.warming {
            self.mean_t += dt;
            self.y = self.y + (x - self.y) * (dt / self.mean_t);
            self.warming = self.mean_t < tau;
            return self.y;
        }
        let e = self.y - x;
        self.y = x + e * self.ee + self.v * self.ev;
        self.v = e * self.ve + self.v * self.vv;
        self.y
    }

    fn codec(&mut self, c: &mut dyn Codec) {
        c.f64(&mut self.dt);
        c.f64(&mut self.tau);
        for k in [&mut self.ee, &mut self.ev, &mut self.ve, &mut self.vv] {
            c.f64(k);
        }
        c.vec3(&mut self.y);
        c.vec3(&mut self.v);
        c.bool(&mut self.warming);
        c.f64(&mut self.mean_t);
    }
}

const UP: Vec3 = Vec3::new(0.0, 0.0, 1.0);

/// `Quat::from_two_vectors(a, UP)` with the terms that multiply UP's zeros left out:
/// with `f = a/|a|`, `cos = f·UP = f_z` and `f × UP = (f_y, −f_x, 0)`. The same bits
/// except for the sign of a zero component (a test checks). Half a turn (a pointing down)
/// goes to the general function. For `|a|²` in `[1e-12, 1e30]`, as the update's earth
/// vector is (`Robust::update`), both norms are in `inv_sqrt`'s fast range: `|f|² = 1`
/// and `|[1 + f_z, f_y, −f_x, 0]|² = 2 (1 + f_z) > 2e-12`.
#[inline(always)]
fn to_up(a: Vec3) -> Quat {
    let f = a.normalized_in_range();
    if f.z < -1.0 + 1e-12 {
        return to_up_general(a);
    }
    Quat::new(1.0 + f.z, f.y, -f.x, 0.0).normalized_in_range()
}

/// [`to_up`]'s rare case, out of line: inlined, the general function's code changed the
/// registers of the whole step.
#[cold]
#[inline(never)]
fn to_up_general(a: Vec3) -> Quat {
    Quat::from_two_vectors(a, UP)
}

/// The heading correction `q_δ = cos(δ/2) + sin(δ/2) k`, a rotation by δ about the
/// vertical, kept as its half-angle pair `(c, s)` with `c ≥ 0` (δ in [−π, π]).
///
/// The readable form keeps δ: `δ ← wrap(δ + k·wrap(atan2(f_x, f_y) − δ))`, then
/// `q_δ = (cos(δ/2), sin(δ/2))` from `sincos` for every output. [`Turn::corrected`] computes
/// the same from the pair: the error `wrap(atan2(f_x, f_y) − δ)` is the azimuth of the field
/// turned by δ, and `q_δ` turns by `k` times it. Small errors (|tan| ≤ 1/4) and small
/// turns (under 1/8 rad) take series; neither `atan2` nor `sincos` runs in the usual step,
/// which is what this form pays for (docs/PERFORMANCE.md has the count).
/// `turn_is_the_readable_heading_step` tests it against the readable form.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Turn {
    c: f64,
    s: f64,
}

impl Turn {
    const IDENTITY: Turn = Turn { c: 1.0, s: 0.0 };

    /// `q_δ` itself (what [`Turn::times`] is tested against).
    #[cfg(test)]
    fn quat(self) -> Quat {
        Quat::new(self.c, 0.0, 0.0, self.s)
    }

    /// `q_δ ⊗ q` with q_δ's zero components left out: `(c + s k)(w + x i + y j + z k)`.
    /// IEEE arithmetic does not fold a product by zero away; the bits are the general
    /// product's for finite values, up to the sign of a zero result
    /// (`the_turn_product_is_the_hamilton_product` checks).
    #[inline(always)]
    fn times(self, q: Quat) -> Quat {
        let (c, s) = (self.c, self.s);
        Quat::new(c * q.w - s * q.z, c * q.x - s * q.y, c * q.y + s * q.x, c * q.z + s * q.w)
    }

    /// `wrap(atan2(f.x, f.y) − δ)`: the azimuth (from north towards east) of the field
    /// `f_e` (ENU) after the turn by δ, `x′ = x cos δ − y sin δ`, `y′ = x sin δ + y cos δ`.
    #[inline(always)]
    fn error(self, f_e: Vec3) -> f64 {
        let (cos_d, sin_d) = (self.c * self.c - self.s * self.s, 2.0 * self.c * self.s);
        let x = f_e.x * cos_d - f_e.y * sin_d;
        let y = f_e.x * sin_d + f_e.y * cos_d;
        crate::math::atan2(x, y)
    }

    /// The turn followed by a further `φ` about the vertical (rad, |φ| ≤ π), with `c ≥ 0`
    /// kept: past δ = ±π the pair changes sign, as `sincos(wrap(δ)/2)` does.
    #[inline(always)]
    fn turned(self, phi: f64) -> Turn {
        let h = 0.5 * phi;
        let (ch, sh) = crate::math::cos_sin(h);
        let (c, s) = (self.c * ch - self.s * sh, self.s * ch + self.c * sh);
        // Both factors are unit to rounding: one Newton step for 1/√(c² + s²) from 1.
        let n = 1.5 - 0.5 * (c * c + s * s);
        if c < 0.0 {
            Turn { c: -c * n, s: -s * n }
        } else {
            Turn { c: c * n, s: s * n }
        }
    }

    /// The heading step: `q_δ` turned by `k` times the error of the field `f_e` (the update
    /// spells it out to keep the error).
    #[cfg(test)]
    fn corrected(self, k: f64, f_e: Vec3) -> Turn {
        self.turned(k * self.error(f_e))
    }

    fn valid(&self) -> bool {
        (self.c * self.c + self.s * self.s - 1.0).abs() <= 1e-9 && self.c >= 0.0
    }
}

/// A field counts towards confirming the reference, or towards a new one, only while the
/// sensor turns at least this fast (rad/s; VQF's `magNewMinGyr`, 20 °/s): turning is what
/// tells a field fixed in the room from a magnet fixed to the sensor.
const MAG_NEW_MIN_GYRO: f64 = 20.0 * core::f64::consts::PI / 180.0;
/// Seconds of turning with the reference accepted that confirm it (VQF's
/// `magNewFirstTime`).
const MAG_CONFIRM_TIME: f64 = 5.0;
/// Seconds a different, consistent field must be seen while turning before it replaces a
/// confirmed reference (VQF's `magNewTime`).
const MAG_NEW_TIME: f64 = 20.0;
/// The same for a reference never confirmed by turning (learned at rest: it may be a
/// disturbance the sensor started in).
const MAG_FIRST_TIME: f64 = 3.0;

/// The heading error covariance of (H1)-(H4) in the module documentation.
#[derive(Clone, Copy, Debug, PartialEq)]
struct HeadingVariance {
    p_ee: f64,
    p_eb: f64,
    p_bb: f64,
    /// (H5): the low-passed heading innovation ȳ (rad) and the evidence J (rad²).
    innov: f64,
    evidence: f64,
}

/// (H4): the variance of a heading uniform on the circle.
const HEADING_VAR_MAX: f64 = core::f64::consts::PI * core::f64::consts::PI / 3.0;

/// (H1′): the fastest rate a MEMS gyroscope reports of real motion (rad/s): 2000 °/s, the
/// largest full scale of common parts (BMI270, LSM6DSO, MPU-9250, ICM-42688).
const PLAUSIBLE_RATE: f64 = 2000.0 * core::f64::consts::PI / 180.0;

/// (H5): c, the share of the innovation evidence J counted in the variance (chosen by
/// cross-validation on BROAD, module documentation).
const INNOVATION_SHARE: f64 = 1.0;

/// (H5): g², the gate on ȳ² in units of the innovation variance the model explains,
/// P_ee + σ_v²: (2σ)².
const INNOVATION_GATE: f64 = 4.0;

/// (H5): τ_y, the time constant of the innovation low-pass (s; cross-validation).
const INNOVATION_TAU: f64 = 4.0;

impl HeadingVariance {
    fn start(s: &RobustSettings) -> HeadingVariance {
        HeadingVariance { p_ee: 0.0, p_eb: 0.0, p_bb: s.bias_sigma * s.bias_sigma, innov: 0.0, evidence: 0.0 }
    }

    /// The reported variance: (H5)'s sum, within (H4)'s cap.
    fn reported(&self) -> f64 {
        (self.p_ee + INNOVATION_SHARE * self.evidence).min(HEADING_VAR_MAX)
    }

    /// (H5): one innovation y (rad) of an accepted field whose variance is `var_v`, with
    /// the gains of the innovation low-pass `k_y` and of the heading correction `k`.
    fn innovation_step(&mut self, y: f64, var_v: f64, k_y: f64, k: f64) {
        let d = y - self.innov;
        // Across ±π the innovation is the same angle: restart there, not average.
        self.innov = if d.abs() > core::f64::consts::PI { y } else { self.innov + d * k_y };
        let y2 = self.innov * self.innov;
        let unexplained = if y2 > INNOVATION_GATE * (self.p_ee + var_v) { y2 } else { 0.0 };
        self.evidence = (self.evidence * (1.0 - k)).max(unexplained);
    }

    /// (H5): the heading was set by a host or from one field: evidence about the one
    /// before it no longer applies.
    fn forget_innovation(&mut self) {
        self.innov = 0.0;
        self.evidence = 0.0;
    }

    /// (H1) and (H4).
    fn gyro_step(&mut self, dt: f64, turned: f64, s: &RobustSettings) {
        let (sigma_g, sigma_w, sigma_b, sigma_s) =
            (s.gyro_noise, s.bias_walk, s.bias_sigma, s.gyro_scale_sigma);
        self.p_ee +=
            2.0 * dt * self.p_eb + dt * dt * self.p_bb + sigma_g * sigma_g * dt + sigma_s * sigma_s * turned;
        if turned > PLAUSIBLE_RATE * dt {
            // (H1′) a reading no MEMS gyroscope reports of real motion: its whole turn may
            // be error.
            self.p_ee += turned * turned;
        }
        self.p_eb += dt * self.p_bb;
        self.p_bb = (self.p_bb + sigma_w * sigma_w * dt).min(sigma_b * sigma_b);
        self.keep_covariance();
        if self.p_ee.is_nan() || self.p_ee > HEADING_VAR_MAX {
            self.lost();
        }
    }

    /// Keeps |P_eb| within √(P_ee P_bb), which the cap on P_bb and rounding could
    /// break: tested with two products, the root taken only when it is needed.
    #[inline(always)]
    fn keep_covariance(&mut self) {
        if self.p_eb * self.p_eb > self.p_ee * self.p_bb {
            // max/min, not clamp: no panic on a NaN (readings beyond the runner's bounds
            // fed to the core directly), which the lost-heading test below then resets.
            let bound = (self.p_ee * self.p_bb).sqrt();
            self.p_eb = self.p_eb.max(-bound).min(bound);
        }
    }

    /// New settings: a larger σ_b adds its increase to P_bb, a smaller one caps it (as
    /// the next (H1) step would).
    fn configure(&mut self, old: &RobustSettings, new: &RobustSettings) {
        let (before, after) = (old.bias_sigma * old.bias_sigma, new.bias_sigma * new.bias_sigma);
        self.p_bb = (self.p_bb + (after - before).max(0.0)).min(after);
        self.keep_covariance();
    }

    /// (H2).
    fn bias_step(&mut self, k_b: f64, sigma_r: f64) {
        self.p_bb = (1.0 - k_b) * (1.0 - k_b) * self.p_bb + k_b * (2.0 - k_b) * sigma_r * sigma_r;
        self.p_eb *= 1.0 - k_b;
    }

    /// (H3), and (H4) for a σ_m set beyond it.
    fn heading_step(&mut self, k: f64, sigma_m: f64) {
        self.p_ee = (1.0 - k) * (1.0 - k) * self.p_ee + k * (2.0 - k) * sigma_m * sigma_m;
        self.p_eb *= 1.0 - k;
        if self.p_ee > HEADING_VAR_MAX {
            self.lost();
        }
    }

    /// (H4): the heading is anything.
    fn lost(&mut self) {
        self.p_ee = HEADING_VAR_MAX;
        self.p_eb = 0.0;
    }

    /// What (H1)-(H4) can leave: variances in range, and a covariance (|P_eb|² ≤ P_ee P_bb,
    /// to rounding).
    fn valid(&self) -> bool {
        use super::holds;
        holds::within(self.p_ee, 0.0, HEADING_VAR_MAX)
            && holds::rate_variance(self.p_bb)
            // (H1) adds dt P_bb ≥ 0 to P_eb and (H2)-(H4) scale it by 1 − k ≥ 0 or zero it:
            // never negative. A negative one could take P_ee below zero at the next step.
            && self.p_eb >= 0.0
            && self.p_eb * self.p_eb <= self.p_ee * self.p_bb * (1.0 + 1e-12) + 1e-300
            // (H5): ȳ is a mean of innovations in [−π, π]; J one of its squares, decayed.
            && holds::within(self.innov, -core::f64::consts::PI, core::f64::consts::PI)
            && holds::within(self.evidence, 0.0, core::f64::consts::PI * core::f64::consts::PI)
    }

    fn codec(&mut self, c: &mut dyn Codec) {
        c.f64(&mut self.p_ee);
        c.f64(&mut self.p_eb);
        c.f64(&mut self.p_bb);
        c.f64(&mut self.innov);
        c.f64(&mut self.evidence);
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
}

impl Robust {
    pub fn new(settings: RobustSettings) -> Robust {
        Robust {
            heading_var: HeadingVariance::start(&settings),
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
    /// detection and the hard-iron consistency clock start over; the bias, the magnetic
    /// reference and a hard-iron offset in use are kept.
    pub(crate) fn reacquire(&mut self, r: &super::Reacquisition) -> bool {
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
        use super::holds;
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
    /// `f64::MIN_POSITIVE`), every value the step computes is finite:
    /// - Every low-pass (rest detector, bias at rest, magnetic reference and candidate,
    ///   hard iron) moves by a gain `dt / (τ + dt)` in [0, 1] towards a bounded input:
    ///   it stays between its old value and its input. The Butterworth low-pass is the
    ///   exact flow of a stable system (its coefficients have |·| ≤ √2 max(1, τ, 2/τ)),
    ///   so its state stays within a constant factor of its inputs and its own bound.
    /// - Products are bounded by the readings' bounds: the largest squares are the
    ///   magnetometer's, below 1e30 (the hard-iron spread of a field 10 times the bound);
    ///   `dt² P_bb` is below 1e12 · 1e10.
    /// - Every division and normalisation has a divisor bounded away from zero:
    ///   quaternions are products of unit ones (so their squared norms, near 1, are in
    ///   `inv_sqrt`'s fast range, and are normalised without its range test); the
    ///   accelerometer's earth vector is tested (`1e-12`), the motion-bias scale divides
    ///   by a norm only when it exceeds a non-negative limit; the low-pass gains divide by
    ///   τ + dt > 0; the heading error divides x′ by y′ only when y′ > 4|x′| (a quotient
    ///   under 1/4); a magnetometer reading's rotated norm is its own (nonzero) norm to
    ///   rounding, and a difference of fields that vanishes gives a NaN dip that fails
    ///   every comparison and is never stored.
    /// - Angles: `sin`/`cos` of any finite argument (|ω| dt up to 2e11 rad) are finite;
    ///   `asin` sees a clamped argument, `atan2` finite ones.
    /// - Clocks grow by dt at most per step and saturate in floating point before
    ///   overflowing.
    ///
    /// A step from a state at the very ends of `valid`'s bounds may leave one a little
    /// beyond them (the low-pass's output up to about 3e14 from a rate of 1e12, a bias
    /// component up to √3 times its bound after the motion estimate's rescaling); the
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
        }
        self.q_gyr = (self.q_gyr * rotation_of(gyro - self.bias, dt)).normalized_in_range();
        self.heading_var.gyro_step(dt, (gyro - self.bias).norm() * dt, s);
        if let Some(a) = accel {
            step.used_accel = true;
            self.correct_inclination(dt, a);
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

    fn correct_inclination(&mut self, dt: f64, a: Vec3) {
        let s = &self.settings;
        let a_i = self.q_gyr.rotate(a);
        if !self.acc_seen {
            self.acc_lp.start(a_i);
            self.acc_seen = true;
        }
        let a_e = self.q_inc.rotate(self.acc_lp.filter(dt, s.tau_acc, a_i));
        if a_e.norm_squared() < 1e-12 {
            return;
        }
        let c = to_up(a_e);
        // While the low-pass still averages its first readings the corrections undo the
        // start's error, not a bias's drift: nothing is learned from them.
        if !self.rest.at_rest() && s.bias_tau_motion > 0.0 && !self.acc_lp.warming {
            // The correction c undoes the drift of the last step; in the sensor frame,
            // -2 c.xyz / dt is the rate the bias error added.
            let drift = (self.q_inc * self.q_gyr).rotate_inverse(c.vector() * 2.0);
            let mut b = self.bias - drift * (1.0 / s.bias_tau_motion);
            // The motion estimate may not grow the bias past the limit, but a larger bias
            // learned at rest (a drifting one, tracked through the rest gate) is kept.
            let (n, limit) = (b.norm(), s.bias_limit.max(self.bias.norm()));
            if n > limit {
                b = b * (limit / n);
            }
            self.bias = b;
        }
        self.q_inc = (c * self.q_inc).normalized_in_range();
    }

    /// Corrects heading from one magnetometer reading; true when it was used.
    fn correct_heading(&mut self, dt: f64, m: Vec3, q_e: Quat) -> bool {
        let s = self.settings;
        // The raw reading in E′, its norm and dip: computed once for the reference, the
        // tests, the new-field candidate and the correction.
        let raw = q_e.rotate(m);
        let (raw_norm, raw_dip) = (raw.norm(), dip(raw));
        if self.mag_count == 0 {
            self.ref_norm = raw_norm;
            self.ref_dip = raw_dip;
        }
        // A compensation in use is kept while it passes: a small offset leaves the raw
        // field within the tests at some orientations, where it would turn the heading.
        // The field used, in E′, with its norm and dip.
        let compensated = || {
            let f_e = q_e.rotate(m - self.hard_iron);
            (f_e, f_e.norm(), dip(f_e))
        };
        let field = match self.hard_iron_on.then(compensated) {
            Some((f_e, n, d)) if self.accepts_norm_dip(n, d) => Some((f_e, n, d)),
            _ if self.accepts_norm_dip(raw_norm, raw_dip) => {
                // The hard-iron estimate and its clock are kept: a small offset lets the
                // raw field pass at some orientations, and starting over at each would
                // never let the estimate complete at high sample rates.
                self.hard_iron_on = false;
                Some((raw, raw_norm, raw_dip))
            }
            _ => {
                self.hard_iron_on = false;
                self.estimate_hard_iron(dt, m, q_e);
                None
            }
        };
        self.mag_disturbed = field.is_none();
        let turning = self.rest.gyro_lp().norm() >= MAG_NEW_MIN_GYRO;
        if field.is_some() && turning {
            self.ref_confirmed = (self.ref_confirmed + dt).min(MAG_CONFIRM_TIME);
        }
        self.new_field(dt, raw_norm, raw_dip, turning);
        // A field parallel to gravity has no horizontal part and gives no heading: a dip
        // within 1e-6 rad of vertical (horizontal at most about 1e-6 of the norm, the
        // EKF's bound) is not used.
        let heading = field.filter(|&(_, _, d)| d.abs() < core::f64::consts::FRAC_PI_2 - 1e-6);
        let Some((f_e, f_norm, f_dip)) = heading else { return false };
        self.mag_count = self.mag_count.saturating_add(1);
        // The first samples are averaged (gain 1/n) until the exponential gain is larger.
        let k_mag = lp_gain(dt, s.tau_mag);
        let k = k_mag.max(1.0 / self.mag_count as f64);
        // `Turn::corrected`, with the innovation kept for (H5).
        let y = self.turn.error(f_e);
        self.turn = self.turn.turned(k * y);
        let (dn, dd) = ((f_norm - self.ref_norm) / self.ref_norm, f_dip - self.ref_dip);
        let kappa = s.mag_deviation_gain;
        let var_v = s.mag_heading_sigma * s.mag_heading_sigma + kappa * kappa * (dn * dn + dd * dd);
        self.heading_var.heading_step(k, var_v.sqrt());
        let kr = lp_gain(dt, 10.0 * s.tau_mag).max(1.0 / self.mag_count as f64);
        // While the first fields are averaged the innovation is the start heading's
        // offset from north, not an error: no evidence.
        if k == k_mag {
            self.heading_var.innovation_step(y, var_v, lp_gain(dt, INNOVATION_TAU), k);
        }
        // A compensated field may be larger than any reading (a large hard-iron offset
        // taken away); the reference stays within what a reading's norm can be, as
        // `valid` requires.
        self.ref_norm = (self.ref_norm + (f_norm - self.ref_norm) * kr).min(super::holds::MAG_NORM_MAX);
        self.ref_dip += (f_dip - self.ref_dip) * kr;
        true
    }

    /// Tracks a candidate field (norm and dip of the raw readings in E′, low-passed while
    /// consistent). When the readings are rejected and the candidate has stayed
    /// consistent while the sensor turned for [`MAG_NEW_TIME`] (or [`MAG_FIRST_TIME`]
    /// when the reference was never confirmed by turning), it becomes the reference: the
    /// reference was a disturbance (a start inside a magnet's field) or the place changed.
    /// A magnet attached to the sensor changes the norm and dip as the sensor turns, so
    /// it never becomes a consistent candidate. When the new field is far from the old
    /// reference the heading starts over from it as at start (averaging gain), since it
    /// came from a disturbance. `n`, `d`: norm and dip of the raw reading in E′.
    fn new_field(&mut self, dt: f64, n: f64, d: f64, turning: bool) {
        let s = self.settings;
        if (n - self.cand_norm).abs() <= s.mag_norm_th * self.cand_norm
            && (d - self.cand_dip).abs() <= s.mag_dip_th
        {
            if turning {
                self.cand_clock += dt;
            }
            let k = lp_gain(dt, s.tau_mag);
            self.cand_norm += (n - self.cand_norm) * k;
            self.cand_dip += (d - self.cand_dip) * k;
        } else {
            self.cand_clock = 0.0;
            self.cand_norm = n;
            self.cand_dip = d;
        }
        let wait = if self.ref_confirmed >= MAG_CONFIRM_TIME { MAG_NEW_TIME } else { MAG_FIRST_TIME };
        if self.mag_disturbed && self.cand_clock >= wait {
            // A field far from the old reference (beyond twice the disturbance tests)
            // shows that the old one was a disturbance, and the heading learned from it
            // wrong; a nearby one is the same place seen better, and the heading stays.
            let far = (self.cand_norm - self.ref_norm).abs() > 2.0 * s.mag_norm_th * self.ref_norm
                || (self.cand_dip - self.ref_dip).abs() > 2.0 * s.mag_dip_th;
            self.ref_norm = self.cand_norm;
            self.ref_dip = self.cand_dip;
            self.ref_confirmed = 0.0;
            self.cand_clock = 0.0;
            if far {
                self.mag_count = 1;
                self.heading_var.lost();
                self.heading_var.forget_innovation();
            }
            self.hard_iron_on = false;
            self.hi_started = false;
            self.hi_clock = 0.0;
        }
    }

    fn accepts(&self, f_e: Vec3) -> bool {
        self.accepts_norm_dip(f_e.norm(), dip(f_e))
    }

    /// The norm and dip tests against the reference.
    fn accepts_norm_dip(&self, norm: f64, dip: f64) -> bool {
        let s = &self.settings;
        (norm - self.ref_norm).abs() <= s.mag_norm_th * self.ref_norm
            && (dip - self.ref_dip).abs() <= s.mag_dip_th
    }

    /// One step of the hard-iron estimate: the reading minus the reference field seen at
    /// the current orientation. Switches compensation on once consistent long enough.
    fn estimate_hard_iron(&mut self, dt: f64, m: Vec3, q_e: Quat) {
        let s = self.settings;
        if s.hard_iron_time <= 0.0 {
            return;
        }
        let (sd, cd) = libm::sincos(self.ref_dip);
        let reference = Vec3::new(0.0, self.ref_norm * cd, -self.ref_norm * sd);
        let inst = m - self.q.rotate_inverse(reference);
        if !self.hi_started {
            self.hi_lp = inst;
            self.hi_spread = 0.0;
            self.hi_started = true;
        }
        let k = lp_gain(dt, s.rest_tau.max(0.25 * s.hard_iron_time));
        self.hi_lp = self.hi_lp + (inst - self.hi_lp) * k;
        self.hi_spread += ((inst - self.hi_lp).norm_squared() - self.hi_spread) * k;
        if !(self.hi_lp.is_finite() && self.hi_spread.is_finite()) {
            // Only a reading beyond the runner's bounds (a core driven directly) gets here:
            // the estimate starts over at the next disturbed reading instead of keeping a
            // NaN that the orientation's guard would never see.
            self.hi_started = false;
            self.hi_lp = Vec3::ZERO;
            self.hi_spread = 0.0;
            self.hi_clock = 0.0;
            return;
        }
        let tol = 0.5 * s.mag_norm_th * self.ref_norm;
        if self.hi_spread.sqrt() < tol && self.accepts(q_e.rotate(m - self.hi_lp)) {
            self.hi_clock += dt;
            if self.hi_clock >= s.hard_iron_time {
                self.hard_iron = self.hi_lp;
                self.hard_iron_on = true;
            }
        } else {
            // A leaky clock: a single noisy reading does not start the wait over (which
            // would make the wait depend on the sample rate); a third of failing readings
            // or more keeps it from ever completing.
            self.hi_clock = (self.hi_clock - 2.0 * dt).max(0.0);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const G: Vec3 = Vec3::new(0.0, 0.0, 9.81);
    /// An earth field in ENU (µT): north and down, dip about 63°.
    const FIELD: Vec3 = Vec3::new(0.0, 20.0, -40.0);
    const DT: f64 = 0.01;

    /// Wraps an angle into (-π, π].
    fn wrap(a: f64) -> f64 {
        use core::f64::consts::{PI, TAU};
        if a > PI {
            a - TAU
        } else if a <= -PI {
            a + TAU
        } else {
            a
        }
    }

    /// The readable heading step of [`Turn`]: δ itself, `atan2` and `sincos`.
    fn readable_heading_step(delta: f64, k: f64, f_e: Vec3) -> Turn {
        let target = libm::atan2(f_e.x, f_e.y);
        let delta = wrap(delta + k * wrap(target - delta));
        let (s, c) = libm::sincos(0.5 * delta);
        Turn { c, s }
    }

    /// [`Turn::corrected`] against the readable step, from random headings, fields and
    /// gains: fields near the turned north (the series), anywhere (libm), and the first
    /// sample's gain 1 (a turn of up to π). The pairs agree as rotations within 4 ulp
    /// (`c ≥ 0` leaves the sign free only at δ = ±π) and the error within 4 ulp of π.
    #[test]
    #[cfg_attr(miri, ignore = "long loops: too slow under Miri")]
    fn turn_is_the_readable_heading_step() {
        use core::f64::consts::PI;
        let mut u = crate::math::test_uniform(97);
        let mut series = 0;
        for i in 0..40000 {
            let delta = if i % 97 == 0 { PI } else { PI * u() };
            let (s, c) = libm::sincos(0.5 * delta);
            let turn = Turn { c, s };
            // The field's azimuth: within 1/4 rad of the turned north, or anywhere.
            let azimuth = if i % 2 == 0 { delta + u() / 4.0 } else { PI * u() };
            let (h, z) = (20.0 + 30.0 * u(), 40.0 * u());
            let f_e = Vec3::new(h * libm::sin(azimuth), h * libm::cos(azimuth), z);
            let k = match i % 4 {
                0 => 1.0,
                1 => 0.5 * (u() + 1.0),
                _ => 10f64.powf(-5.0 + 4.0 * 0.5 * (u() + 1.0)),
            };
            let e = turn.error(f_e);
            let want_e = wrap(libm::atan2(f_e.x, f_e.y) - delta);
            let de = (e - want_e).abs();
            assert!(de.min(2.0 * PI - de) <= 4.0 * f64::EPSILON * PI, "{delta} {f_e:?}: {e} vs {want_e}");
            series += usize::from(4.0 * libm::tan(e).abs() < 0.99 && e.abs() < 1.0);
            let got = turn.corrected(k, f_e);
            let want = readable_heading_step(delta, k, f_e);
            let apart = |a: Turn, b: Turn| (a.c - b.c).abs().max((a.s - b.s).abs());
            let d = apart(got, want).min(apart(got, Turn { c: -want.c, s: -want.s }));
            assert!(d <= 4.0 * f64::EPSILON, "{delta} {f_e:?} {k}: {got:?} vs {want:?}");
            assert!(got.valid(), "{got:?}");
        }
        assert!(series > 15000, "{series} steps took the series");
    }

    /// [`Turn::times`] gives the general Hamilton product's bits.
    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn the_turn_product_is_the_hamilton_product() {
        let mut u = crate::math::test_uniform(6);
        for _ in 0..1000 {
            let (s, c) = libm::sincos(3.0 * u());
            let turn = Turn { c: c.abs(), s };
            let q = Quat::new(u(), u(), u(), u()).normalized();
            let (got, want) = (turn.times(q), turn.quat() * q);
            assert_eq!(
                [got.w, got.x, got.y, got.z].map(f64::to_bits),
                [want.w, want.x, want.y, want.z].map(f64::to_bits),
                "{turn:?} {q:?}"
            );
        }
    }

    /// A compensated field larger than any reading (readings near the bound, a hard-iron
    /// offset opposite to them, the widest norm test) is used, and the reference norm's
    /// low-pass stays within what `valid` accepts: the state still saves and loads.
    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn a_large_compensated_field_keeps_the_reference_valid() {
        use crate::filters::holds::MAG_NORM_MAX;
        use crate::filters::MAX_MAG;
        let settings = RobustSettings { mag_norm_th: 10.0, ..RobustSettings::default() };
        let mut f = Robust::new(settings);
        let m = Vec3::new(0.0, 0.99 * MAX_MAG, -0.99 * MAX_MAG);
        (f.mag_count, f.ref_norm, f.ref_dip) = (5, 0.9 * MAG_NORM_MAX, dip(m));
        (f.hard_iron_on, f.hard_iron) = (true, m * -1.0);
        assert!(f.valid());
        assert!(f.correct_heading(DT, m, Quat::IDENTITY), "the compensated field 2m is used");
        assert_eq!(f.ref_norm, MAG_NORM_MAX);
        assert!(f.valid(), "{f:?}");
    }

    /// A state loaded with its three output factors at `holds::unit`'s limit (|·|² =
    /// 1 ± 0.99e-9) stays one `valid` accepts through gyroscope-only steps,
    /// which leave q_inc and q_δ as loaded and multiply them into the output without a
    /// normalisation: its blob still loads.
    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn factors_at_the_unit_limit_leave_a_valid_output() {
        for e in [0.99e-9f64, -0.99e-9] {
            let k = (1.0 + e).sqrt();
            let mut f = Robust::new(RobustSettings::default());
            let q_inc = Quat::from_axis_angle(Vec3::new(1.0, 0.0, 0.0), 0.1);
            let (s, c) = libm::sincos(0.4);
            (f.q_inc, f.turn) = (q_inc.scale(k), Turn { c: c * k, s: s * k });
            f.q_gyr = Quat::from_axis_angle(Vec3::new(0.0, 1.0, 0.0), 0.2).scale(k);
            f.q = f.turn.times(f.q_inc * f.q_gyr);
            assert!(f.valid(), "{e}: loaded state {f:?}");
            for _ in 0..100 {
                f.update(DT, Vec3::new(0.1, -0.2, 0.3), None, None).unwrap();
                assert!(f.valid(), "{e}: {f:?}");
            }
            // Past what `holds::unit` allows a single quaternion: the case this covers.
            assert!((f.q.norm_squared() - 1.0).abs() > 1.5e-9, "{e}: {}", f.q.norm_squared() - 1.0);
        }
    }

    /// A million small corrections keep the pair unit to rounding: each step's Newton
    /// normalisation takes out what the products add.
    #[test]
    #[cfg_attr(miri, ignore = "long loops: too slow under Miri")]
    fn the_turn_stays_unit() {
        let mut u = crate::math::test_uniform(5);
        let mut turn = Turn::IDENTITY;
        let mut worst = 0.0f64;
        for _ in 0..1_000_000 {
            let f_e = Vec3::new(20.0 * u(), 20.0 + u(), -40.0);
            turn = turn.corrected(0.01 * (u() + 1.0), f_e);
            worst = worst.max((turn.c * turn.c + turn.s * turn.s - 1.0).abs());
        }
        assert!(worst <= 4.0 * f64::EPSILON, "{worst:e}");
    }

    fn filter(settings: RobustSettings, q: Quat) -> Robust {
        let mut f = Robust::new(settings);
        f.set_quaternion(q);
        f
    }

    /// Feeds `seconds` of samples of the true orientation `q(t)` with rate `w(t)`.
    fn run(
        f: &mut Robust,
        seconds: f64,
        mut truth: impl FnMut(f64) -> (Quat, Vec3, Vec3),
        mag: impl Fn(f64, Quat) -> Option<Vec3>,
    ) {
        let n = (seconds / DT).round() as usize;
        for i in 0..n {
            let t = i as f64 * DT;
            let (q, w, lin) = truth(t);
            let accel = q.rotate_inverse(G + lin);
            f.update(DT, w, Some(accel), mag(t, q)).unwrap();
        }
    }

    fn heading(q: Quat) -> f64 {
        q.to_euler().yaw
    }

    fn inclination(est: Quat, truth: Quat) -> f64 {
        let up = Vec3::new(0.0, 0.0, 1.0);
        let a = est.rotate_inverse(up);
        let b = truth.rotate_inverse(up);
        libm::atan2(a.cross(b).norm(), a.dot(b))
    }

    /// [`to_up`] is `Quat::from_two_vectors(a, UP)` bit for bit (zeros compared by value)
    /// over random directions, including near and at half a turn.
    #[test]
    #[cfg_attr(miri, ignore = "long loops: too slow under Miri")]
    fn to_up_is_from_two_vectors_to_up() {
        let mut u = crate::math::test_uniform(23);
        for i in 0..20000 {
            let a = match i {
                0 => Vec3::new(0.0, 0.0, -9.81),
                1 => Vec3::new(1e-7, 0.0, -9.81),
                2 => Vec3::new(0.0, 0.0, 3.0),
                _ => Vec3::new(u(), u(), u()) * (10.0 * (u() + 1.0)),
            };
            let (got, want) = (to_up(a), Quat::from_two_vectors(a, UP));
            for (x, y) in [(got.w, want.w), (got.x, want.x), (got.y, want.y), (got.z, want.z)] {
                assert!(x == y, "{a:?}: {got:?} vs {want:?}");
            }
        }
    }

    /// A magnitude at the ends or in the middle of `[0, bound)`, of either sign when
    /// `signed`: what the randomised tests below put in states, settings and samples.
    fn extreme(u: &mut dyn FnMut() -> f64, bound: f64, signed: bool) -> f64 {
        let r = 0.5 * (u() + 1.0);
        let x = match (4.0 * (u() + 1.0)) as usize {
            0 => 0.0,
            1 => f64::MIN_POSITIVE,
            2 => bound * (1.0 - 1e-9),
            3 => bound * 0.999,
            4 => bound * r,
            5 => bound * 10f64.powf(-15.0 * r),
            6 => bound * 10f64.powf(-300.0 * r),
            _ => bound * 1e-6 * r,
        };
        if signed && u() < 0.0 {
            -x
        } else {
            x
        }
    }

    /// Writes a value at the ends of its range into every field a snapshot holds, in the
    /// codec's order: `bounds[i]` is the i-th number's bound, negative for one that is
    /// never negative.
    struct Forge<'a, U: FnMut() -> f64> {
        u: &'a mut U,
        bounds: &'a [f64],
        i: usize,
    }

    impl<U: FnMut() -> f64> Codec for Forge<'_, U> {
        fn u64(&mut self, v: &mut u64) {
            // Only `mag_count` (bools are below).
            *v = [0, 1, 1000, u32::MAX as u64][(2.0 * ((self.u)() + 1.0)) as usize];
        }
        fn f64(&mut self, v: &mut f64) {
            let b = self.bounds[self.i];
            *v = extreme(self.u, b.abs(), b > 0.0);
            self.i += 1;
        }
        fn bool(&mut self, v: &mut bool) {
            *v = (self.u)() < 0.0;
        }
        fn fail(&mut self) {
            unreachable!()
        }
    }

    /// The argument at [`Robust::update`], tried: states at the ends of what `valid`
    /// accepts (every field forged, then the quaternions, the low-pass's coefficients and
    /// the heading covariance made consistent), settings at the ends of their ranges, and
    /// samples at the ends of the runner's bounds (dt from 1e-9 to 1e6 s, each component
    /// under its bound, squared norms from `f64::MIN_POSITIVE`), stepped 20 times from each
    /// of 4,000 states: every number of the state stays finite after every step.
    #[test]
    #[cfg_attr(miri, ignore = "long loops: too slow under Miri")]
    fn no_accepted_sample_makes_the_step_non_finite() {
        use crate::filters::params::{Settings, MAX_PARAMS};
        use crate::filters::{MAX_ACCEL, MAX_DT, MAX_GYRO, MAX_MAG, MIN_DT};
        use core::f64::consts::PI;
        let mut u = crate::math::test_uniform(31);
        let (rate, acc, mag) = (10.0 * MAX_GYRO, 10.0 * MAX_ACCEL, 10.0 * MAX_MAG);
        let norm = 3f64.sqrt() * MAX_MAG;
        #[rustfmt::skip]
        let bounds = [
            1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, // q_gyr, q_inc, q_δ, q
            rate, rate, rate, // bias
            1.0, 1.0, 1.0, 1.0, 1.0, 1.0, acc, acc, acc, 1e12, 1e12, 1e12, -1e6, // low-pass
            rate, rate, rate, acc, acc, acc, acc, acc, acc, -1e300, // rest detector
            -norm, PI, mag, mag, mag, -(2.0 * mag) * (2.0 * mag), -1e300, mag, mag, mag, // magnetic
            -MAG_CONFIRM_TIME, -norm, PI, -1e300, // reference confirmation, candidate
            1.0, 1.0, 1.0, // heading covariance
            PI, -PI * PI, // innovation low-pass and evidence (H5)
        ];
        let unit = |u: &mut dyn FnMut() -> f64| Quat::new(u(), u(), u(), u()).normalized();
        let reading = |u: &mut dyn FnMut() -> f64, bound: f64| loop {
            let mut c = || extreme(&mut *u, bound, true);
            let v = Vec3::new(c(), c(), c());
            if v.norm_squared() >= f64::MIN_POSITIVE {
                return v;
            }
        };
        for case in 0..4000 {
            let mut slots = [0.0; MAX_PARAMS];
            RobustSettings::default().write_slots(&mut slots);
            for p in PARAMS {
                let r = 0.5 * (u() + 1.0);
                slots[p.id as usize] = match (5.0 * r) as usize {
                    0 => p.min,
                    1 => p.max,
                    2 if p.zero_off => 0.0,
                    3 if p.min > 0.0 => p.min * (p.max / p.min).powf(0.5 * (u() + 1.0)),
                    _ => p.default,
                };
            }
            let settings = RobustSettings::from_slots(&slots);
            let mut f = Robust::new(settings);
            f.codec(&mut Forge { u: &mut u, bounds: &bounds, i: 0 });
            (f.q_gyr, f.q_inc, f.q) = (unit(&mut u), unit(&mut u), unit(&mut u));
            let (s, c) = libm::sincos(PI * u());
            f.turn = Turn { c: c.abs(), s };
            let dt0 = MIN_DT * (MAX_DT / MIN_DT).powf(0.5 * (u() + 1.0));
            f.acc_lp.coefficients(dt0, settings.tau_acc);
            let h = &mut f.heading_var;
            h.p_ee = extreme(&mut u, HEADING_VAR_MAX, false);
            h.p_bb = extreme(&mut u, rate * rate, false);
            h.p_eb = (h.p_ee * h.p_bb).sqrt() * (0.5 * (u() + 1.0));
            assert!(f.valid(), "case {case}: forged state not valid: {f:?}");
            for _ in 0..20 {
                let dt = match (4.0 * (u() + 1.0)) as usize {
                    0 => MIN_DT,
                    1 => MAX_DT,
                    _ => MIN_DT * (MAX_DT / MIN_DT).powf(0.5 * (u() + 1.0)),
                };
                let gyro = Vec3::new(
                    extreme(&mut u, MAX_GYRO, true),
                    extreme(&mut u, MAX_GYRO, true),
                    extreme(&mut u, MAX_GYRO, true),
                );
                let accel = (u() < 0.6).then(|| reading(&mut u, MAX_ACCEL));
                let m = (u() < 0.6).then(|| reading(&mut u, MAX_MAG));
                let before = f.clone();
                f.step(dt, gyro, accel, m);
                let mut check = Finite(true);
                f.codec(&mut check);
                assert!(
                    check.0,
                    "case {case}: dt {dt}, {gyro:?}, {accel:?}, {m:?} from {before:?} gave {f:?}"
                );
            }
        }
    }

    /// A codec that finds whether every number is finite.
    struct Finite(bool);

    impl Codec for Finite {
        fn u64(&mut self, _: &mut u64) {}
        fn f64(&mut self, v: &mut f64) {
            self.0 &= v.is_finite();
        }
        fn fail(&mut self) {}
    }

    /// Readings beyond the runner's bounds that leave the orientation finite, driven into
    /// the core directly: NaN, overflowing and infinite magnetometer readings while the
    /// field is disturbed. The hard-iron estimate starts over, and good samples then leave
    /// a state `valid` accepts (a NaN kept in the estimate would fail it).
    #[test]
    #[cfg_attr(miri, ignore = "long loops: too slow under Miri")]
    fn an_absurd_magnetometer_reading_leaves_no_nan_behind() {
        let still = |_: f64| (Quat::IDENTITY, Vec3::ZERO, Vec3::ZERO);
        let mut f = filter(RobustSettings::default(), Quat::IDENTITY);
        run(&mut f, 2.0, still, |_, q| Some(q.rotate_inverse(FIELD)));
        for bad in [
            Vec3::new(f64::NAN, 0.0, 0.0),
            Vec3::new(1e200, 1e200, 1e200),
            Vec3::new(f64::INFINITY, 0.0, 1.0),
        ] {
            run(&mut f, 0.5, still, |_, q| Some(q.rotate_inverse(FIELD * 3.0)));
            for _ in 0..3 {
                assert!(f.update(DT, Vec3::ZERO, Some(G), Some(bad)).is_some());
            }
            run(&mut f, 0.5, still, |_, q| Some(q.rotate_inverse(FIELD * 3.0)));
            run(&mut f, 0.5, still, |_, q| Some(q.rotate_inverse(FIELD)));
            assert!(f.valid(), "{bad:?}: {f:?}");
        }
    }

    /// The guard: readings beyond the runner's bounds that do make the step non-finite
    /// return `None`, keep the orientation from before the step, the settings and the
    /// bias, and good samples then bring the filter back.
    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn a_non_finite_step_starts_over_from_the_orientation_before_it() {
        let q = Quat::from_axis_angle(Vec3::new(1.0, 2.0, 3.0).normalized(), 0.7);
        let mut f = filter(RobustSettings::default(), q);
        f.bias = Vec3::new(0.01, -0.02, 0.005);
        assert!(f.update(DT, Vec3::new(f64::NAN, 0.0, 0.0), Some(q.rotate_inverse(G)), None).is_none());
        assert_eq!(f.quaternion(), q);
        assert_eq!(f.bias(), Vec3::new(0.01, -0.02, 0.005));
        assert_eq!(f.settings, RobustSettings::default());
        assert_eq!(f.heading_sigma(), HEADING_VAR_MAX.sqrt());
        let mut good = f.clone();
        good.restart(q);
        assert_eq!(f, good);
        // Still at q, with the gyroscope reading the bias.
        let (a, m) = (q.rotate_inverse(G), q.rotate_inverse(FIELD));
        for _ in 0..500 {
            let step = f.update(DT, Vec3::new(0.01, -0.02, 0.005), Some(a), Some(m));
            assert!(step.is_some_and(|s| s.used_accel && s.used_mag));
        }
        assert!(inclination(f.quaternion(), q) < 1e-3);
        assert!(f.heading_sigma() < 0.1);
        assert!(f.valid());
    }

    /// The series for `exp(−x) (cos x, sin x)` against libm's `exp` and `sincos`, term
    /// for term of the readable form, over its range (x from 1e-9 to 1/32, log-uniform,
    /// and the ends): each within 2⁻⁵¹ (relative for `E S`); past the range it declines.
    /// Against 200-bit arithmetic (mpmath, same x) the series is the closer of the two:
    /// at most 0.27 and 0.73 units of 2⁻⁵² relative, the libm form 0.73 and 1.13, so the
    /// bound is their two errors.
    #[test]
    #[cfg_attr(miri, ignore = "long loops: too slow under Miri")]
    fn the_low_pass_coefficient_series_is_the_libm_form() {
        let mut u = crate::math::test_uniform(31);
        let (mut worst_c, mut worst_s) = (0.0f64, 0.0f64);
        for i in 0..20000 {
            let x = match i {
                0 => f64::MIN_POSITIVE,
                1 => 1.0 / 32.0 - f64::EPSILON / 32.0,
                _ => 10f64.powf(-9.0 + (9.0 - 32f64.log10()) * 0.5 * (u() + 1.0)),
            };
            let (sc, ss) = exp_turn_series(x).expect("within the series' range");
            let (lc, ls) = exp_turn(x);
            worst_c = worst_c.max((sc - lc).abs());
            worst_s = worst_s.max((ss - ls).abs() / ls);
        }
        assert!(
            worst_c <= 2.0 * f64::EPSILON && worst_s <= 2.0 * f64::EPSILON,
            "E C {worst_c:e}, E S {worst_s:e}"
        );
        assert_eq!(exp_turn_series(1.0 / 32.0), None);
        assert_eq!(exp_turn_series(-1e-3), None);
        assert_eq!(exp_turn_series(f64::NAN), None);
    }

    /// A state holding libm's coefficients for its dt and τ (a snapshot written before
    /// the series) is valid; coefficients 1e-12 away from their dt and τ's are not.
    #[test]
    fn coefficients_from_before_the_series_stay_valid() {
        let mut f = Butterworth::default();
        f.settle(Vec3::new(0.1, -0.2, 9.8));
        let mut differ = 0;
        for (dt, tau) in [(0.0035, 3.0), (0.01, 0.5), (0.004, 0.13), (0.0071, 1.7), (0.02, 0.9)] {
            f.coefficients(dt, tau);
            assert!(f.valid());
            // The coefficients exactly as the code before the series computed them.
            let e = libm::exp(-dt / tau);
            let (s, c) = libm::sincos(dt / tau);
            let old = Butterworth {
                ee: e * (c + s),
                ev: e * s * tau,
                ve: -2.0 * e * s / tau,
                vv: e * (c - s),
                ..f.clone()
            };
            assert!(old.valid(), "dt {dt}, tau {tau}");
            differ += usize::from(old != f);
            assert!(!Butterworth { ev: f.ev * (1.0 + 1e-12), ..f.clone() }.valid());
            assert!(!Butterworth { vv: f.vv * (1.0 - 1e-12), ..f.clone() }.valid());
        }
        assert!(differ > 0, "libm's coefficients were the series' in every case");
    }

    /// One step is the flow of `ÿ = ω² (x − y) − 2ζω ẏ` (ζ = 1/√2, ω = √2/τ) over dt with
    /// the input held: against a fine fourth-order Runge-Kutta integration of that
    /// equation, over steps of mixed lengths.
    #[test]
    #[cfg_attr(miri, ignore = "long loops: too slow under Miri")]
    fn the_low_pass_steps_its_differential_equation_exactly() {
        let (zeta, tau) = (core::f64::consts::FRAC_1_SQRT_2, 0.8);
        let omega = core::f64::consts::SQRT_2 / tau;
        let deriv = |x: f64, y: f64, v: f64| (v, omega * omega * (x - y) - 2.0 * zeta * omega * v);
        let (mut y, mut v) = (0.0, 0.0);
        let mut f = Butterworth::default();
        f.settle(Vec3::ZERO);
        for i in 0..300 {
            let dt = [0.01, 0.003, 0.25, 1.7][i % 4];
            let x = (i as f64 * 0.37).sin() + 1.0;
            let n = 2000;
            let h = dt / n as f64;
            for _ in 0..n {
                let k1 = deriv(x, y, v);
                let k2 = deriv(x, y + 0.5 * h * k1.0, v + 0.5 * h * k1.1);
                let k3 = deriv(x, y + 0.5 * h * k2.0, v + 0.5 * h * k2.1);
                let k4 = deriv(x, y + h * k3.0, v + h * k3.1);
                y += h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
                v += h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
            }
            let got = f.filter(dt, tau, Vec3::new(x, 0.0, 0.0)).x;
            assert!((got - y).abs() < 1e-10, "step {i} (dt {dt}): {got} vs {y}");
        }
    }

    /// A steady input passes unchanged whatever the steps, and a step response stays
    /// bounded for every τ in the parameter's range at any dt and any mix of dt.
    #[test]
    #[cfg_attr(miri, ignore = "long loops: too slow under Miri")]
    fn the_low_pass_is_stable_for_every_dt_and_tau() {
        let spec = PARAMS.iter().find(|p| p.id == id::ROBUST_TAU_ACC).unwrap();
        let mut taus = vec![spec.min, spec.max, spec.default];
        let mut t = spec.min;
        while t < spec.max {
            taus.push(t);
            t *= 1.37;
        }
        let v = Vec3::new(0.3, -9.0, 2.0);
        for &tau in &taus {
            for dt in [1e-9, 1e-4, 0.001, 0.0123, 0.1, 0.7, 3.0, 100.0] {
                let mut f = Butterworth::default();
                f.settle(v);
                for k in 0..50 {
                    let y = f.filter(if k % 3 == 0 { dt } else { 0.01 }, tau, v);
                    assert!((y - v).norm() < 1e-7 * v.norm(), "tau {tau}, dt {dt}: {y:?}");
                }
                // A unit step: a Butterworth overshoots by about 4 %.
                let mut f = Butterworth::default();
                f.settle(Vec3::ZERO);
                for k in 0..2000 {
                    let y = f.filter(if k % 5 == 0 { 0.01 } else { dt }, tau, Vec3::new(1.0, 0.0, 0.0)).x;
                    assert!(y.is_finite() && y.abs() < 1.05, "tau {tau}, dt {dt}: {y}");
                }
            }
        }
    }

    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn learns_the_bias_at_rest() {
        let bias = Vec3::new(0.01, -0.02, 0.015);
        let q = Quat::from_axis_angle(Vec3::new(1.0, 0.0, 0.0), 0.3);
        let mut f = filter(RobustSettings::default(), q);
        run(&mut f, 20.0, |_| (q, bias, Vec3::ZERO), |_, q| Some(q.rotate_inverse(FIELD)));
        assert!(f.at_rest());
        assert!((f.bias() - bias).norm() < 1e-5, "{:?}", f.bias());
        // Heading drifted before the bias was learned; the tilt did not.
        assert!(inclination(f.quaternion(), q) < 1e-3);
    }

    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn a_slow_turn_is_not_rest() {
        // 1 deg/s about a horizontal axis: under rest_gyro, but the accelerometer tilts.
        let w = Vec3::new(0.0175, 0.0, 0.0);
        let mut f = filter(RobustSettings::default(), Quat::IDENTITY);
        let mut seen_rest = false;
        for i in 0..3000 {
            let q = rotation_of(w, i as f64 * DT);
            f.update(DT, w, Some(q.rotate_inverse(G)), None).unwrap();
            seen_rest |= f.at_rest();
        }
        assert!(!seen_rest);
        assert!(f.bias().norm() < 1e-3, "{:?}", f.bias());
    }

    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn rejects_zero_mean_linear_acceleration() {
        // 4 m/s² along east at 1 Hz: an accelerometer-only tilt swings by about 22°.
        let q = Quat::from_axis_angle(Vec3::new(0.3, 1.0, 0.2), 0.5);
        let mut f = filter(RobustSettings::default(), q);
        let mut worst: f64 = 0.0;
        for i in 0..2000 {
            let t = i as f64 * DT;
            let lin = Vec3::new(4.0 * libm::sin(core::f64::consts::TAU * t), 0.0, 0.0);
            f.update(DT, Vec3::ZERO, Some(q.rotate_inverse(G + lin)), None).unwrap();
            // The first tau_acc averages the readings so far (a mean over 2.5 periods
            // still carries 0.5 m/s² of the acceleration, 3°); the low-pass, started from
            // that mean, has shed it by 2 tau_acc.
            if t >= 2.0 * RobustSettings::default().tau_acc {
                worst = worst.max(inclination(f.quaternion(), q));
            }
        }
        assert!(worst.to_degrees() < 1.5, "{}", worst.to_degrees());
    }

    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn holds_heading_through_a_disturbance_and_resumes_without_a_jump() {
        let q = Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), 0.7);
        let settings = RobustSettings { hard_iron_time: 0.0, ..Default::default() };
        let mut f = filter(settings, q);
        let clean = |_: f64, q: Quat| Some(q.rotate_inverse(FIELD));
        run(&mut f, 5.0, |_| (q, Vec3::ZERO, Vec3::ZERO), clean);
        let before = heading(f.quaternion());
        // A magnet in the room: 30 µT more along east, fixed in the earth frame.
        let magnet = |_: f64, q: Quat| Some(q.rotate_inverse(FIELD + Vec3::new(30.0, 0.0, 0.0)));
        run(&mut f, 10.0, |_| (q, Vec3::ZERO, Vec3::ZERO), magnet);
        assert!(f.mag_disturbed());
        assert!((heading(f.quaternion()) - before).abs() < 1e-9);
        let mut steps = Vec::new();
        for _ in 0..500 {
            let h = heading(f.quaternion());
            run(&mut f, DT, |_| (q, Vec3::ZERO, Vec3::ZERO), clean);
            steps.push((heading(f.quaternion()) - h).abs());
        }
        assert!(!f.mag_disturbed());
        assert!(
            steps.iter().all(|s| *s < 1e-3),
            "largest step {:?}",
            steps.iter().cloned().fold(0.0, f64::max)
        );
        assert!((heading(f.quaternion()) - 0.7).abs() < 1e-3);
    }

    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn compensates_a_magnet_attached_to_the_sensor() {
        let hard = Vec3::new(25.0, -10.0, 15.0);
        let w = Vec3::new(0.0, 0.0, 0.5);
        let q0 = Quat::from_axis_angle(Vec3::new(1.0, 0.0, 0.0), 0.2);
        let mut f = filter(RobustSettings::default(), q0);
        let truth = |t: f64| {
            let q = q0 * rotation_of(w, t);
            (q, w, Vec3::ZERO)
        };
        // Clean, then the magnet: the raw field fails the norm test from then on.
        let mag = |t: f64, q: Quat| Some(q.rotate_inverse(FIELD) + if t >= 5.0 { hard } else { Vec3::ZERO });
        run(&mut f, 30.0, truth, mag);
        let h = f.hard_iron().expect("compensation on");
        assert!((h - hard).norm() < 0.5, "{h:?}");
        assert!(!f.mag_disturbed());
        assert!(f.quaternion().angle_to(truth(30.0).0) < 0.01);
    }

    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn estimates_bias_in_motion_from_the_inclination_correction() {
        let bias = Vec3::new(0.01, -0.008, 0.0);
        let settings = RobustSettings { bias_tau_motion: 10.0, ..Default::default() };
        let mut f = filter(settings, Quat::IDENTITY);
        let mut q = Quat::IDENTITY;
        for i in 0..60_000 {
            let t = i as f64 * DT;
            let w = Vec3::new(0.4 * libm::sin(0.3 * t), 0.4 * libm::cos(0.2 * t), 0.3);
            q = q * rotation_of(w, DT);
            f.update(DT, w + bias, Some(q.rotate_inverse(G)), None).unwrap();
        }
        assert!(!f.at_rest());
        // Rotation about all axes makes every component observable from gravity.
        assert!((f.bias() - bias).norm() < 1e-3, "{:?}", f.bias());
    }

    /// (H1) alone, without noise or walk, is a bias error of σ_b integrated: σ_b t; (H3)
    /// alone settles to σ_m whatever the sample rate; (H2) to σ_r likewise.
    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn the_heading_model_steps_its_equations() {
        let s = RobustSettings { gyro_noise: 0.0, bias_walk: 0.0, ..Default::default() };
        let mut p = HeadingVariance::start(&s);
        for _ in 0..1000 {
            p.gyro_step(DT, 0.0, &s);
        }
        let t = 1000.0 * DT;
        assert!((p.p_ee.sqrt() - s.bias_sigma * t).abs() < 1e-12 * t, "{p:?}");
        assert!((p.p_eb - s.bias_sigma * s.bias_sigma * t).abs() < 1e-15 * t);
        for dt in [1e-3, 1e-2, 0.1] {
            let k = lp_gain(dt, s.tau_mag);
            let mut h = HeadingVariance { p_ee: 1.0, p_eb: 0.0, p_bb: 1.0, innov: 0.0, evidence: 0.0 };
            for _ in 0..(100.0 * s.tau_mag / dt) as usize {
                h.heading_step(k, s.mag_heading_sigma);
                h.bias_step(lp_gain(dt, s.bias_tau_rest), s.bias_sigma_rest);
            }
            assert!((h.p_ee.sqrt() - s.mag_heading_sigma).abs() < 1e-9, "{dt} {h:?}");
            assert!((h.p_bb.sqrt() - s.bias_sigma_rest).abs() < 1e-9, "{dt} {h:?}");
        }
        // A first field (gain 1) sets σ_m at once; (H4) caps a heading that is anything.
        p.heading_step(1.0, s.mag_heading_sigma);
        assert_eq!((p.p_ee, p.p_eb), (s.mag_heading_sigma * s.mag_heading_sigma, 0.0));
        for _ in 0..100_000 {
            p.gyro_step(1.0, 0.0, &s);
        }
        assert_eq!(p.p_ee, HEADING_VAR_MAX);
        assert!(p.valid());
    }

    /// Simulated truth: a sensor turning about the vertical with a vertical gyro bias of
    /// 0.3 °/s (within the default σ_b) and no rest. While a magnet in the room is
    /// rejected the heading drifts as b t and the reported σ grows every step, covering
    /// the error; once the field is trusted again σ falls back to its floor (σ_m and the
    /// lag b τ_mag the unlearned bias leaves, also covered).
    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn the_heading_uncertainty_grows_while_the_field_is_distrusted() {
        let s = RobustSettings { hard_iron_time: 0.0, ..Default::default() };
        let mut f = Robust::new(s);
        let (rate, bias) = (0.5, 0.3f64.to_radians());
        let up = Vec3::new(0.0, 0.0, 1.0);
        let truth = |t: f64| Quat::from_axis_angle(up, rate * t);
        let error = |f: &Robust, t: f64| wrap(heading(f.quaternion()) - heading(truth(t))).abs();
        let mut t = 0.0;
        let step = |f: &mut Robust, magnet: Vec3, t: &mut f64| {
            *t += DT;
            let q = truth(*t);
            let m = q.rotate_inverse(FIELD + magnet);
            f.update(DT, up * (rate + bias), Some(q.rotate_inverse(G)), Some(m)).unwrap();
        };
        for _ in 0..3000 {
            step(&mut f, Vec3::ZERO, &mut t);
        }
        let settled = f.heading_sigma();
        assert!(!f.mag_disturbed() && error(&f, t) < 2.0 * settled, "{} {settled}", error(&f, t));
        // Without a rest the floor is σ_m and the lag σ_b τ_mag of an unlearned bias
        // (nearly reached after 30 s, 3.3 τ_mag).
        let floor = s.mag_heading_sigma.hypot(s.bias_sigma * s.tau_mag);
        assert!((settled - floor).abs() < 0.05 * floor, "{settled} {floor}");
        let (mut last, start) = (settled, error(&f, t));
        // 15 s: a field that stays different for 20 s while turning is taken as the
        // place's (`new_field`).
        for _ in 0..1500 {
            step(&mut f, Vec3::new(30.0, 0.0, 0.0), &mut t);
            assert!(f.mag_disturbed());
            let sigma = f.heading_sigma();
            assert!(sigma > last, "{sigma} after {last}");
            assert!(error(&f, t) < 2.0 * sigma, "error {} sigma {sigma}", error(&f, t));
            last = sigma;
        }
        let drift = error(&f, t) - start;
        assert!(last > 1.5 * settled && drift > 0.9 * bias * 15.0, "{last} {settled} {drift}");
        for _ in 0..6000 {
            step(&mut f, Vec3::ZERO, &mut t);
            assert!(error(&f, t) < 2.0 * f.heading_sigma().max(settled));
        }
        assert!((f.heading_sigma() - settled).abs() < 0.05 * settled, "{} {settled}", f.heading_sigma());
    }

    /// (H1) and (H3)'s evidence: the same turning sensor reports a larger σ when the
    /// field it uses is off the reference in norm and dip (a disturbance the tests let
    /// through) than in a clean field, and when it turns faster; without the magnetometer
    /// σ grows at every step, and a clean field brings it back to the clean floor.
    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn the_heading_uncertainty_follows_the_fields_deviation_and_the_turning() {
        let s = RobustSettings { hard_iron_time: 0.0, ..Default::default() };
        let up = Vec3::new(0.0, 0.0, 1.0);
        let settle = |rate: f64, disturbance: Vec3| {
            let mut f = Robust::new(s);
            let turning = move |t: f64| (Quat::from_axis_angle(up, rate * t), up * rate, Vec3::ZERO);
            // A rest teaches the bias (else its lag σ_b τ_mag hides the rest); 10 s clean
            // (the reference), then 30 s in the given field.
            let still = |_: f64| (Quat::IDENTITY, Vec3::ZERO, Vec3::ZERO);
            run(&mut f, 20.0, still, |_, q| Some(q.rotate_inverse(FIELD)));
            run(&mut f, 10.0, turning, |_, q| Some(q.rotate_inverse(FIELD)));
            run(
                &mut f,
                30.0,
                move |t| turning(t + 10.0),
                move |_, q| Some(q.rotate_inverse(FIELD + disturbance)),
            );
            f
        };
        let clean = settle(0.5, Vec3::ZERO);
        // Norm 6 % low and dip 6.9 deg shallower: within the tests (10 %, 10 deg).
        let off = settle(0.5, Vec3::new(3.0, 3.0, 5.0));
        assert!(!off.mag_disturbed());
        let (c, o) = (clean.heading_sigma(), off.heading_sigma());
        assert!(o > 1.15 * c, "deviation: {o} vs clean {c}");
        let fast = settle(3.0, Vec3::ZERO).heading_sigma();
        assert!(fast > 1.1 * c, "turning fast: {fast} vs {c}");
        // Without the magnetometer (6D) σ grows at every step; a clean field brings it back.
        let mut f = clean;
        let turning = |t: f64| (Quat::from_axis_angle(up, 0.5 * t), up * 0.5, Vec3::ZERO);
        let mut last = f.heading_sigma();
        for i in 0..1000 {
            let (q, w, _) = turning(40.0 + i as f64 * DT);
            f.update(DT, w, Some(q.rotate_inverse(G)), None).unwrap();
            assert!(f.heading_sigma() > last);
            last = f.heading_sigma();
        }
        assert!(last > 1.3 * c, "{last} {c}");
        // Back to the clean floor, which the bias walk since the rest has raised a little.
        run(&mut f, 60.0, move |t| turning(t + 50.0), |_, q| Some(q.rotate_inverse(FIELD)));
        assert!(f.heading_sigma() < 1.2 * c && f.heading_sigma() < 0.8 * last, "{} {c}", f.heading_sigma());
    }

    /// Every path that changes the heading or the settings moves the covariance with it:
    /// the bias walk up to its cap, a host's orientation (exact), a gap re-acquired with
    /// the magnetometer (σ_m) or without (anything), a larger σ_b (added) or a smaller
    /// one (capped), a reference field replaced by a far one (anything, then averaged).
    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn the_heading_covariance_follows_every_path() {
        let s = RobustSettings { gyro_noise: 0.0, ..Default::default() };
        let mut p = HeadingVariance {
            p_ee: 0.0,
            p_eb: 0.0,
            p_bb: s.bias_sigma_rest * s.bias_sigma_rest,
            innov: 0.0,
            evidence: 0.0,
        };
        let t = 100.0;
        p.gyro_step(t, 0.0, &s);
        let walked = s.bias_sigma_rest * s.bias_sigma_rest + s.bias_walk * s.bias_walk * t;
        assert!(walked < s.bias_sigma * s.bias_sigma && (p.p_bb - walked).abs() < 1e-18, "{p:?}");
        p.gyro_step(1e6, 0.0, &s);
        assert_eq!(p.p_bb, s.bias_sigma * s.bias_sigma);
        assert!(p.valid());

        let mut f = Robust::new(s);
        let up = Vec3::new(0.0, 0.0, 1.0);
        let turning = |t: f64| (Quat::from_axis_angle(up, 0.5 * t), up * 0.5, Vec3::ZERO);
        run(&mut f, 10.0, turning, |_, q| Some(q.rotate_inverse(FIELD)));
        let settled = f.heading_sigma();
        f.set_quaternion(f.quaternion());
        assert_eq!(f.heading_sigma(), 0.0);
        let (q, a) = (f.quaternion(), f.quaternion().rotate_inverse(G));
        let gap = |mag: Option<Vec3>| crate::filters::Reacquisition {
            keep: q,
            with_mag: None,
            dt: 1.0,
            gyro: Vec3::ZERO,
            accel: a,
            mag,
            still: None,
        };
        assert!(f.reacquire(&gap(Some(q.rotate_inverse(FIELD)))));
        assert_eq!(f.heading_sigma(), s.mag_heading_sigma);
        assert!(!f.reacquire(&gap(None)));
        assert_eq!(f.heading_sigma() * f.heading_sigma(), HEADING_VAR_MAX);

        let p_bb = f.heading_var.p_bb;
        let wider = RobustSettings { bias_sigma: 2.0 * s.bias_sigma, ..s };
        f.heading_var.configure(&s, &wider);
        assert!((f.heading_var.p_bb - (p_bb + 3.0 * s.bias_sigma * s.bias_sigma)).abs() < 1e-18);
        let narrower = RobustSettings { bias_sigma: 0.1 * s.bias_sigma, ..s };
        f.heading_var.configure(&wider, &narrower);
        assert_eq!(f.heading_var.p_bb, narrower.bias_sigma * narrower.bias_sigma);
        assert!(f.heading_var.valid());

        // A far field (half as strong again) that stays while turning replaces the
        // reference after MAG_NEW_TIME: the heading learned from the old one is anything.
        let mut f = Robust::new(s);
        run(&mut f, 10.0, turning, |_, q| Some(q.rotate_inverse(FIELD)));
        let mut peak: f64 = 0.0;
        for i in 0..3000 {
            let t = 10.0 + i as f64 * DT;
            let (q, w, _) = turning(t);
            f.update(DT, w, Some(q.rotate_inverse(G)), Some(q.rotate_inverse(FIELD * 1.5))).unwrap();
            peak = peak.max(f.heading_sigma());
        }
        assert!(peak > 0.5 && f.heading_sigma() < 2.0 * settled, "{peak} {} {settled}", f.heading_sigma());
    }

    /// A rest teaches the bias, and the heading uncertainty then grows at σ_r, not σ_b.
    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn a_rest_slows_the_growth() {
        let s = RobustSettings::default();
        let grow = |rest: bool| {
            let mut f = Robust::new(s);
            let still = |_: f64| (Quat::IDENTITY, Vec3::ZERO, Vec3::ZERO);
            if rest {
                run(&mut f, 20.0, still, |_, _| None);
                assert!(f.at_rest());
            }
            let before = f.heading_sigma();
            let turning = |t: f64| {
                let w = Vec3::new(0.0, 0.0, 0.5);
                (Quat::from_axis_angle(w.normalized(), 0.5 * t), w, Vec3::ZERO)
            };
            run(&mut f, 30.0, turning, |_, _| None);
            f.heading_sigma() - before
        };
        let (with, without) = (grow(true), grow(false));
        assert!(with < 0.2 * without, "{with} {without}");
        assert!((without - s.bias_sigma * 30.0).abs() < 0.05 * without, "{without}");
    }

    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn butterworth_has_unit_gain_and_settles() {
        let mut b = Butterworth::default();
        let x = Vec3::new(1.0, -2.0, 3.0);
        b.settle(x);
        for _ in 0..10 {
            assert!((b.filter(0.01, 2.5, x) - x).norm() < 1e-12);
        }
        // A step from zero reaches 1 - 1/e within about tau, never overshooting 5 %.
        let mut b = Butterworth::default();
        b.settle(Vec3::ZERO);
        let mut y = Vec3::ZERO;
        let mut peak: f64 = 0.0;
        for _ in 0..2000 {
            y = b.filter(0.01, 2.5, x);
            peak = peak.max(y.x);
        }
        assert!((y - x).norm() < 2e-3 && peak < 1.05, "{y:?} {peak}");
    }
}

/// The common lifecycle's view of this kind (see [`super::estimator::Estimator`]).
mod estimator_impl {
    use super::*;
    use crate::filters::estimator::estimator;
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
    });
}
