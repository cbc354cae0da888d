//! McGinnis et al.'s PI complementary filter: gains active only at rest, initial bias
//! and attitude from a stationary period.
//!
//! Source: R. S. McGinnis et al., "Validation of complementary filter based IMU data
//! fusion for tracking torso angle and rifle orientation", IMECE2014-36909
//! (`shared/papers/mcginnis-2014-complementary-filter.txt`). Equation numbers are the
//! paper's. Per sample:
//!
//! 1. `g_a = a_m / |a_m|` (6);
//! 2. `ω̃ = ω_m − ω_b(t−dt)` (7); propagate `C̃ = C · exp(ω̃ dt)` and take
//!    `g_ω = C̃ᵀ Ê₃` (8);
//! 3. `θ_e = g_a × g_ω` (9);
//! 4. `ω_b(t) = ω_b(t−dt) − K_I θ_e dt` (10), then `C(t) = C(t−dt) · exp((ω_m − ω_b(t) +
//!    K_P θ_e) dt)`, eq. (4).
//!
//! Choices where the paper is silent or loose:
//! - `C_{G/I}` maps body to ground coordinates (from (1), `Ċ = C ω×`), so it is orient's
//!   `R(q)`; the ground frame G has Ê₃ up. Each step's attitude change is the exact
//!   rotation `exp(ω dt)` ("the numerical integration technique described in \[1\]" is
//!   not given; the exact rotation of a constant rate over dt is used).
//! - Rest: `|ω_m − ω̄| < gyro_rest` and `| |a_m| − g₀ | < accel_rest`, where `ω̄` and `g₀`
//!   are the mean gyroscope reading and accelerometer norm of the start-up period
//!   ("within the sensor noise floors of their stationary values"; zero and the first
//!   norm when the start is given). The stationary value is kept fixed rather than
//!   following ω_b: a bias estimate wound up by a large initial error would otherwise
//!   stop the filter from ever seeing rest again. The paper gives no numbers; the defaults are
//!   about three times the per-sample noise of its sensor (0.03 °/s/√Hz, 650 µg/√Hz)
//!   at 100 Hz, rounded up for hand-held use. The paper gives no K_P, K_I either:
//!   K_P = 1/s settles the attitude with a 1 s time constant at rest. K_I is bounded by
//!   the rest gating: the bias learned at a rest corrects the attitude error accumulated
//!   over the motion before it, and the loop's gain per rest is about K_I·T/K_P for T
//!   seconds of motion, which must stay below 2 (it overshoots and diverges above; the
//!   24-hour test showed this with K_I = 0.05 and 50 s of motion per minute).
//!   K_I = 0.01/s² keeps that gain at or below 1 for rests up to 100 s apart.
//! - Start-up: the first `init_duration` seconds are the stationary period: ω_b = mean
//!   gyroscope; Ê₃ = mean accelerometer direction; Ê₂ = the sensor ê₂ axis projected on
//!   the horizontal plane; Ê₁ = Ê₂ × Ê₃. Native frame: (Ê₁, Ê₂, Ê₃) read as
//!   East-North-Up, so heading is relative to the initial ê₂ projection ("north").
//!   With `align_heading` set and magnetometer readings in the period, the mean field
//!   defines north instead, aligning the output with the configured earth frame.

use crate::filters::kinds::startup::{StartupMeans, Stillness};
use crate::filters::params::{settings, Switch};
use crate::filters::pipeline::estimator::Step;
use crate::filters::pipeline::sample::Usual;
use crate::math::{cos_and_sinc, Frame, Quat, Vec3};

settings! {
    /// The complementary filter's settings.
    pub struct ComplementarySettings {
        kp: f64 = COMPLEMENTARY_KP 24 {
            unit: "1/s",
            default: 1.0,
            min: 0.0,
            max: 1000.0,
            zero_off: false,
            doc: "Proportional gain K_P, eq. (4), applied only at rest; default 1.0 (the paper gives \
                 no value: 1 s attitude time constant at rest).",
        },
        ki: f64 = COMPLEMENTARY_KI 25 {
            unit: "1/s^2",
            default: 0.01,
            min: 0.0,
            max: 1000.0,
            zero_off: false,
            doc: "Integral gain K_I for the gyro bias, eqs. (5) and (10), applied only at rest; \
                 default 0.01 (the paper gives no value): stable for rests up to 100 s apart, since \
                 the loop gain per rest is about K_I * motion time / K_P and must stay below 2.",
        },
        gyro_rest: f64 = COMPLEMENTARY_GYRO_REST 26 {
            unit: "rad/s",
            default: 0.02,
            min: 0.0,
            max: 100.0,
            zero_off: false,
            doc: "Rest when |gyro - start-up mean gyro| is below this; default 0.02 (about 3x the per-sample \
                 noise floor of the paper's 0.03 deg/s/sqrt(Hz) gyro at 100 Hz).",
        },
        accel_rest: f64 = COMPLEMENTARY_ACCEL_REST 27 {
            unit: "m/s^2",
            default: 0.2,
            min: 0.0,
            max: 100.0,
            zero_off: false,
            doc: "Rest when | |accel| - g0 | is below this (g0: start-up mean); default 0.2 (about \
                 3x the per-sample noise floor of the paper's 650 ug/sqrt(Hz) accelerometer).",
        },
        init_duration: f64 = COMPLEMENTARY_INIT_DURATION 28 {
            unit: "s",
            default: 2.0,
            min: 0.0,
            max: 3600.0,
            zero_off: false,
            doc: "Stationary start-up period giving the initial bias and attitude (paper: 'a time \
                 period at the start of a trial'); default 2.",
        },
        align_heading: Switch = COMPLEMENTARY_ALIGN_HEADING 29 {
            unit: "1",
            default: 0.0,
            min: 0.0,
            max: 1.0,
            zero_off: false,
            doc: "1: take north from the start-up mean magnetometer reading, aligning heading with \
                 the earth frame; 0 (default, the paper): heading relative to the sensor y axis.",
        },
    }
    shared { gravity: f64 = GRAVITY }
}

/// McGinnis' complementary filter. Native frame: East-North-Up with "north" from the
/// start-up period (see the module doc).
#[derive(Clone, Debug, PartialEq)]
pub struct Complementary {
    pub settings: ComplementarySettings,
    phase: Phase,
}

/// The start-up period's sums and the state after it share their bytes: the sums are
/// needed only until the period ends, and the state is the initial one until then.
#[derive(Clone, Debug, PartialEq)]
enum Phase {
    Starting(StartupMeans),
    Running(Running),
}

/// The filter's state once it has an orientation.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Running {
    q: Quat,
    bias: Vec3,
    /// g₀: mean accelerometer norm at start-up (m/s²); 0 until known.
    g0: f64,
    /// ω_m's stationary value: the start-up mean (zero without a start-up period).
    b0: Vec3,
    rest: bool,
}

impl Running {
    /// The state before any sample (and during the start-up period).
    const INITIAL: Running =
        Running { q: Quat::IDENTITY, bias: Vec3::ZERO, g0: 0.0, b0: Vec3::ZERO, rest: false };

    /// Stores `q` renormalised. `USUAL`: only when `q` is unit to 1e-8 (`None`, nothing
    /// stored, otherwise).
    #[inline(always)]
    fn commit<const USUAL: bool>(&mut self, q: Quat) -> Option<()> {
        // exp() is unit up to rounding; renormalise so it cannot drift over long runs.
        self.q = if USUAL { q.renormalized_usual()? } else { q.renormalized()? };
        Some(())
    }
}

/// The rotation `exp(ω dt)` as a unit quaternion (exact for a constant rate):
/// `[cos(θ/2), ω sin(θ/2)/|ω|]` with `θ = |ω| dt`.
///
/// The readable form is [`rotation_of_by_sincos`]: one root, one division and one shared
/// range reduction for the sine and cosine. For the usual step, `θ/2 < 1/16` (|ω| up to
/// 12.5 rad/s at 100 Hz), `cos(θ/2)` and `sin(θ/2)/(θ/2)` are their Taylor series to
/// the 8th power, in `(θ/2)² = |ω|² dt²/4` alone: no root, no division and no range
/// reduction ([`cos_and_sinc`]). A test checks every component against the readable
/// form to 3 ulp (2.1 measured).
#[inline]
pub fn rotation_of(omega: Vec3, dt: f64) -> Quat {
    match rotation_of_series(omega, dt) {
        Some(q) => q,
        None => rotation_of_by_sincos(omega, dt),
    }
}

/// [`rotation_of`] by the series, for `θ/2 < 1/16`; `None` beyond.
#[inline(always)]
pub(crate) fn rotation_of_series(omega: Vec3, dt: f64) -> Option<Quat> {
    let h = 0.5 * dt;
    let x2 = omega.norm_squared() * (h * h);
    if x2 < 1.0 / 256.0 {
        let (c, sinc) = cos_and_sinc(x2);
        // sin(θ/2)/|ω| = (sin x / x) · dt/2.
        let k = sinc * h;
        return Some(Quat::new(c, omega.x * k, omega.y * k, omega.z * k));
    }
    None
}

/// [`rotation_of`] with the sine and cosine themselves (`θ/2 ≥ 1/16`, and the readable
/// form the series is tested against).
#[cold]
#[inline(never)]
pub fn rotation_of_by_sincos(omega: Vec3, dt: f64) -> Quat {
    let n = omega.norm();
    let (s, c) = libm::sincos(0.5 * (n * dt));
    if n == 0.0 {
        return Quat::IDENTITY;
    }
    let k = s / n;
    Quat::new(c, omega.x * k, omega.y * k, omega.z * k)
}

impl Complementary {
    pub fn new(settings: ComplementarySettings) -> Complementary {
        Complementary { settings, phase: Phase::Starting(StartupMeans::default()) }
    }

    fn running(&self) -> Running {
        match &self.phase {
            Phase::Running(r) => *r,
            Phase::Starting(_) => Running::INITIAL,
        }
    }

    pub fn quaternion(&self) -> Quat {
        self.running().q
    }

    /// Takes new settings, the state kept but for the rest reference g₀: one that is not
    /// the new configured gravity's within `GRAVITY_STILL` becomes that gravity, or rest,
    /// and with it the correction, would not be seen again.
    pub(crate) fn configure(&mut self, settings: ComplementarySettings) {
        self.settings = settings;
        if let Phase::Running(r) = &mut self.phase {
            r.g0 = crate::filters::kinds::startup::stationary_norm(r.g0, settings.gravity);
        }
    }

    /// A known initial attitude (native frame): the start-up period is skipped; the bias
    /// starts at zero and g₀ is the configured gravity (one reading could be a glitch, and
    /// a wrong g₀ would hide rest, and so the correction, for good).
    pub fn set_quaternion(&mut self, q: Quat) {
        let r = self.running();
        let g0 = if r.g0 == 0.0 { self.settings.gravity } else { r.g0 };
        self.phase = Phase::Running(Running { q, g0, ..r });
    }

    /// After a gap: the attitude from the accelerometer (and, with `align_heading`, the
    /// magnetometer; else the heading held), the bias ω_b and the stationary values kept,
    /// but for the rest watch's still reading, which becomes ω_b, and ω_b0 when it fails
    /// the rest test against the old one.
    pub(crate) fn reacquire(&mut self, r: &crate::filters::pipeline::estimator::Reacquisition) -> bool {
        let (q, used_mag) = match r.with_mag {
            Some(q) if self.settings.align_heading.on() => (q, true),
            _ => (r.keep, false),
        };
        if let Phase::Running(state) = &mut self.phase {
            state.q = q;
            state.rest = false;
            if let Some(g) = r.still {
                // The rest watch's still reading: the bias, and the rest test's reference
                // when the reading fails the rest test against it (a wrong ω_b0 would keep
                // the rest test, and so K_I, off for good; a right one is a mean, better
                // than one reading).
                state.bias = g;
                let gyro_rest = self.settings.gyro_rest;
                if (g - state.b0).norm_squared() >= gyro_rest * gyro_rest {
                    state.b0 = g;
                }
            }
        }
        used_mag
    }

    /// Values an update could leave (see `filters::holds`).
    pub(crate) fn valid(&self) -> bool {
        use crate::filters::state::holds;
        match &self.phase {
            Phase::Running(r) => {
                holds::unit(r.q)
                    && holds::rate(r.bias)
                    && holds::rate(r.b0)
                    && holds::within(r.g0, 0.0, crate::filters::pipeline::sample::MAX_ACCEL * 2.0)
            }
            Phase::Starting(s) => s.valid(),
        }
    }

    /// The snapshot's fields as before the phases shared their bytes: the state, then the
    /// start-up period if one is in progress. A period in progress has the initial
    /// state; a snapshot with another is not one an update wrote, and reads as invalid.
    pub(crate) fn codec(&mut self, c: &mut dyn crate::filters::state::Codec) {
        let mut r = self.running();
        c.quat(&mut r.q);
        c.vec3(&mut r.bias);
        c.f64(&mut r.g0);
        c.vec3(&mut r.b0);
        c.bool(&mut r.rest);
        let mut startup = match &self.phase {
            Phase::Starting(s) => Some(s.clone()),
            Phase::Running(_) => None,
        };
        StartupMeans::codec(&mut startup, c);
        self.phase = match startup {
            None => Phase::Running(r),
            Some(s) if r == Running::INITIAL => Phase::Starting(s),
            Some(_) => Phase::Starting(StartupMeans::invalid()),
        };
    }

    pub fn bias(&self) -> Vec3 {
        self.running().bias
    }

    /// True when the last sample was classified as rest (gains active).
    pub fn at_rest(&self) -> bool {
        self.running().rest
    }

    pub fn initializing(&self) -> bool {
        matches!(self.phase, Phase::Starting(_))
    }

    /// The attitude from the start-up means: Ê₃ up, Ê₂ from the sensor's y axis (or the
    /// field), rows of R_ES = [Ê₁; Ê₂; Ê₃]; and whether the field gave the heading (a
    /// field parallel to gravity gives none).
    fn initial_attitude(settings: &ComplementarySettings, s: &StartupMeans) -> (Quat, bool) {
        let accel = s.accel();
        if settings.align_heading.on() {
            if let Some(q) = s.mag().and_then(|m| Frame::Enu.attitude_from(accel, Some(m))) {
                return (q, true);
            }
        }
        let e3 = accel.normalized();
        let y = Vec3::new(0.0, 1.0, 0.0);
        let mut e2 = y - e3 * y.dot(e3);
        if e2.norm() < 1e-6 {
            // ê₂ vertical: use ê₁ rotated a quarter turn instead (−ê₁ × Ê₃ direction).
            let x = Vec3::new(1.0, 0.0, 0.0);
            e2 = e3.cross(x - e3 * x.dot(e3));
        }
        let e2 = e2.normalized();
        let e1 = e2.cross(e3);
        (Quat::from_matrix([[e1.x, e1.y, e1.z], [e2.x, e2.y, e2.z], [e3.x, e3.y, e3.z]]), false)
    }

    /// Out of line: inlined into the kind dispatch (`Core::update`), it gave that
    /// dispatch a stack frame, six saved registers, that every kind's update paid.
    #[inline(never)]
    pub fn update(&mut self, dt: f64, gyro: Vec3, accel: Option<Vec3>, mag: Option<Vec3>) -> Option<Step> {
        let mut step = Step::default();
        let r = match &mut self.phase {
            Phase::Running(r) => r,
            Phase::Starting(s) => {
                // The wrapper guarantees an accelerometer reading until initialised.
                let a = accel?;
                // Still: within twice the rest thresholds of the period's means.
                let still = Stillness {
                    gyro: 2.0 * self.settings.gyro_rest,
                    accel: 2.0 * self.settings.accel_rest,
                    gravity: self.settings.gravity,
                };
                if !s.add(dt, gyro, a, mag, self.settings.init_duration, still) {
                    // The readings went into the period's means (the field is used only
                    // for north, with align_heading).
                    step.initializing = true;
                    step.used_accel = true;
                    step.used_mag = mag.is_some() && self.settings.align_heading.on();
                    return Some(step);
                }
                let bias = s.bias();
                let (q, used_mag) = Complementary::initial_attitude(&self.settings, s);
                step.used_accel = true;
                step.used_mag = used_mag;
                // A period that never kept still has no stationary norm either: g₀ is then
                // the configured gravity, as its bias is zero.
                let g0 = if s.moved() { self.settings.gravity } else { s.accel_norm() };
                self.phase = Phase::Running(Running { q, bias, g0, b0: bias, rest: false });
                return Some(step);
            }
        };
        let Some(a) = accel else {
            // Gyroscope only: propagate with the bias-corrected rate (no rest test).
            r.commit::<false>(r.q * rotation_of(gyro - r.bias, dt))?;
            r.rest = false;
            return Some(step);
        };
        Complementary::step::<false>(r, &self.settings, dt, gyro, || a.norm(), || a.normalized())
    }

    /// Every setting lets the usual step stand for the update: no option has a path of
    /// its own.
    pub(crate) fn usual_settings(&self) -> bool {
        true
    }

    /// [`Complementary::update`]'s usual case, which calls no function: past the start-up
    /// period with g₀ known, an accelerometer reading, rotations within
    /// [`rotation_of_series`]'s range and an estimate unit to 1e-8 before its
    /// renormalisation. The same result, or `None` with nothing changed otherwise.
    #[inline(always)]
    pub(crate) fn update_usual(&mut self, s: &Usual) -> Option<u32> {
        let (Phase::Running(r), Some(a)) = (&mut self.phase, s.accel) else {
            return None;
        };
        // A field is only counted here, never used (it aligns the heading at start-up
        // alone), so `no_heading`'s rule changes nothing: the flags say MAG_REJECTED
        // either way.
        Complementary::step::<true>(r, &self.settings, s.dt, s.gyro, || a.norm(), || a.unit())
            .map(|st| st.flags(true, s.mag.is_some()))
    }

    /// Eqs. (4)-(10) from the running state with an accelerometer reading, given as its
    /// norm `|a_m|` and direction `ĝ_a` (computed only where used). `USUAL`: see
    /// [`Complementary::update_usual`].
    #[inline(always)]
    fn step<const USUAL: bool>(
        r: &mut Running,
        settings: &ComplementarySettings,
        dt: f64,
        gyro: Vec3,
        a_norm: impl Fn() -> f64,
        g_a: impl FnOnce() -> Vec3,
    ) -> Option<Step> {
        let step = Step { used_accel: true, ..Step::default() };
        let rotation =
            |omega: Vec3| if USUAL { rotation_of_series(omega, dt) } else { Some(rotation_of(omega, dt)) };
        // A known initial attitude skipped the start-up period: g₀ from the first reading.
        // Kept local until the step commits: a refused step changes nothing. The usual
        // step leaves that first reading to the general one, and stores nothing here.
        if USUAL && r.g0 == 0.0 {
            return None;
        }
        let g0 = if r.g0 == 0.0 { a_norm() } else { r.g0 };
        // Rest: |ω_m| and |a_m| near their stationary values (the start-up means). It
        // depends on the readings alone, not on the estimate.
        // |ω_m − ω̄| < gyro_rest compared squared: no square root for the usual case, a
        // moving sensor, whose test ends there.
        let gyro_rest = settings.gyro_rest;
        let rest = (gyro - r.b0).norm_squared() < gyro_rest * gyro_rest
            && (a_norm() - g0).abs() < settings.accel_rest;
        let omega_tilde = gyro - r.bias; // (7)
        let q_tilde = r.q * rotation(omega_tilde)?;
        if rest {
            let g_a = g_a(); // (6)
            let g_omega = q_tilde.z_axis_in_body(); // (8)
            let theta_e = g_a.cross(g_omega); // (9)
            let bias = r.bias - theta_e * (settings.ki * dt); // (10)
            if !bias.is_finite() {
                return None;
            }
            r.commit::<USUAL>(r.q * rotation(gyro - bias + theta_e * settings.kp)?)?; // (4)
            r.bias = bias;
        } else {
            // In motion K_p = K_I = 0: (10) keeps the bias and (4) integrates ω̃, which
            // is the prediction q̃ itself; θ_e has no effect and is not computed.
            r.commit::<USUAL>(q_tilde)?;
        }
        r.rest = rest;
        if !USUAL {
            r.g0 = g0;
        }
        Some(step)
    }
}

#[cfg(test)]
mod tests;

/// The common lifecycle's view of this kind (see [`crate::filters::pipeline::estimator::Estimator`]).
mod estimator_impl {
    use super::*;
    use crate::filters::pipeline::estimator::estimator;
    use crate::filters::Diagnostics;

    estimator!(impl for Complementary { settings: ComplementarySettings, native: Enu, own_startup: true, diagnostics: GYRO_BIAS | REST, usual: true } {
        fn configure(&mut self, settings: ComplementarySettings) {
            Complementary::configure(self, settings);
        }

        #[inline(always)]
        fn update(&mut self, dt: f64, gyro: Vec3, accel: Option<Vec3>, mag: Option<Vec3>) -> Option<Step> {
            Complementary::update(self, dt, gyro, accel, mag)
        }

        fn diagnose(&self, d: &mut Diagnostics) {
            d.gyro_bias = self.bias();
            d.rest = if self.at_rest() { 1.0 } else { 0.0 };
        }

        fn at_rest(&self) -> bool {
            Complementary::at_rest(self)
        }

        fn starting(&self) -> bool {
            matches!(&self.phase, Phase::Starting(s) if s.begun())
        }
    });
}
