//! The inclination correction: the accelerometer low-passed in the almost-inertial frame
//! ([`Butterworth`]) and the rotation that brings it to the vertical.

use super::motion_bias::{Activity, MotionSettings};
use super::*;

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
pub(super) struct Butterworth {
    /// dt and τ the coefficients belong to.
    pub(super) dt: f64,
    pub(super) tau: f64,
    /// One step: `e' = ee·e + ev·ẏ`, `ẏ' = ve·e + vv·ẏ`.
    pub(super) ee: f64,
    pub(super) ev: f64,
    pub(super) ve: f64,
    pub(super) vv: f64,
    /// Output y and its rate ẏ (per second).
    pub(super) y: Vec3,
    pub(super) v: Vec3,
    /// Started with [`Butterworth::start`] and still within the first τ: the output is
    /// the time-weighted mean of the inputs so far (`mean_t` seconds of them).
    pub(super) warming: bool,
    pub(super) mean_t: f64,
}

impl Butterworth {
    pub(super) fn coefficients(&mut self, dt: f64, tau: f64) {
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
    pub(super) fn valid(&self) -> bool {
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
        coefficients
            && crate::filters::state::holds::accel(self.y)
            && self.v.max_abs() < 1e12
            && self.mean_t >= 0.0
    }

    /// Sets the state to the steady state of a constant input `x`.
    pub(super) fn settle(&mut self, x: Vec3) {
        self.y = x;
        self.v = Vec3::ZERO;
        self.warming = false;
    }

    /// Starts from one reading: for the first τ the output is the mean of the readings
    /// so far, then the filter runs from that mean at rest. One reading taken in motion
    /// (a linear acceleration, a vibration) would otherwise stay in the output for
    /// several τ; the mean forgets it as 1/n. (VQF starts its low-passes the same way.)
    pub(super) fn start(&mut self, x: Vec3) {
        self.settle(x);
        self.warming = true;
        self.mean_t = 0.0;
    }

    pub(super) fn filter(&mut self, dt: f64, tau: f64, x: Vec3) -> Vec3 {
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

    pub(super) fn codec(&mut self, c: &mut dyn Codec) {
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

pub(super) const UP: Vec3 = Vec3::new(0.0, 0.0, 1.0);

/// `Quat::from_two_vectors(a, UP)` with the terms that multiply UP's zeros left out:
/// with `f = a/|a|`, `cos = f·UP = f_z` and `f × UP = (f_y, −f_x, 0)`. The same bits
/// except for the sign of a zero component (a test checks). Half a turn (a pointing down)
/// goes to the general function. For `|a|²` in `[1e-12, 1e30]`, as the update's earth
/// vector is (`Robust::update`), both norms are in `inv_sqrt`'s fast range: `|f|² = 1`
/// and `|[1 + f_z, f_y, −f_x, 0]|² = 2 (1 + f_z) > 2e-12`.
#[inline(always)]
pub(super) fn to_up(a: Vec3) -> Quat {
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
pub(super) fn to_up_general(a: Vec3) -> Quat {
    Quat::from_two_vectors(a, UP)
}

impl Robust {
    /// The inclination correction of a sample with the accelerometer reading `a` and the
    /// de-biased rate's squared norm `w2` (for the motion bias filter).
    pub(super) fn correct_inclination(&mut self, dt: f64, a: Vec3, w2: f64) {
        let s = &self.settings;
        let a_i = self.q_gyr.rotate(a);
        if !self.acc_seen {
            self.acc_lp.start(a_i);
            self.motion.start(self.q_inc * self.q_gyr, self.bias);
            self.acc_seen = true;
        }
        // The reading stands for the time since the last one (a gyroscope faster than the
        // accelerometer gives samples without one).
        let held = self.motion.accel_dt(dt);
        let a_lp = self.acc_lp.filter(held, s.tau_acc, a_i);
        // What the low-pass has not averaged out yet: the linear acceleration of the moment.
        let lin2 = (a_i - a_lp).norm_squared();
        let a_e = self.q_inc.rotate(a_lp);
        if a_e.norm_squared() < 1e-12 {
            return;
        }
        let c = to_up(a_e);
        // While the low-pass still averages its first readings the corrections undo the
        // start's error, not a bias's drift: nothing is learned from them (and nothing at
        // rest, where the rest estimate learns the whole bias).
        let learning = !self.rest.at_rest() && s.bias_sigma_motion > 0.0 && !self.acc_lp.warming;
        // The motion estimate may not grow a component past the limit, but a larger bias
        // learned at rest (a drifting one, tracked through the rest gate) is kept.
        let limit = s.bias_limit.max(self.bias.max_abs());
        let motion = MotionSettings {
            tau: s.tau_acc,
            sigma_b: s.bias_sigma,
            sigma_m: s.bias_sigma_motion,
            limit,
            walk: s.bias_walk,
        };
        if let Some(b) = self.motion.update(
            dt,
            self.q_inc * self.q_gyr,
            c,
            self.bias,
            &motion,
            Activity { learning, rate2: w2, lin2 },
        ) {
            self.bias = b;
        }
        self.q_inc = (c * self.q_inc).normalized_in_range();
    }
}
