//! The heading correction, a turn about the vertical ([`Turn`]), and its uncertainty,
//! the heading error covariance of (H1)-(H5) in the kind's documentation.

use super::*;

/// `(E C, E S)` with `E = exp(−x)`, `C = cos x`, `S = sin x`: the readable form, with libm
/// (beyond the series' range, and what the series is tested against).
#[cold]
#[inline(never)]
pub(super) fn exp_turn(x: f64) -> (f64, f64) {
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
pub(super) fn exp_turn_series(x: f64) -> Option<(f64, f64)> {
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
pub(super) struct Turn {
    pub(super) c: f64,
    pub(super) s: f64,
}

impl Turn {
    pub(super) const IDENTITY: Turn = Turn { c: 1.0, s: 0.0 };

    /// `q_δ` itself (what [`Turn::times`] is tested against).
    #[cfg(test)]
    pub(super) fn quat(self) -> Quat {
        Quat::new(self.c, 0.0, 0.0, self.s)
    }

    /// `q_δ ⊗ q` with q_δ's zero components left out: `(c + s k)(w + x i + y j + z k)`.
    /// IEEE arithmetic does not fold a product by zero away; the bits are the general
    /// product's for finite values, up to the sign of a zero result
    /// (`the_turn_product_is_the_hamilton_product` checks).
    #[inline(always)]
    pub(super) fn times(self, q: Quat) -> Quat {
        let (c, s) = (self.c, self.s);
        Quat::new(c * q.w - s * q.z, c * q.x - s * q.y, c * q.y + s * q.x, c * q.z + s * q.w)
    }

    /// `wrap(atan2(f.x, f.y) − δ)`: the azimuth (from north towards east) of the field
    /// `f_e` (ENU) after the turn by δ, `x′ = x cos δ − y sin δ`, `y′ = x sin δ + y cos δ`.
    #[inline(always)]
    pub(super) fn error(self, f_e: Vec3) -> f64 {
        let (cos_d, sin_d) = (self.c * self.c - self.s * self.s, 2.0 * self.c * self.s);
        let x = f_e.x * cos_d - f_e.y * sin_d;
        let y = f_e.x * sin_d + f_e.y * cos_d;
        crate::math::atan2(x, y)
    }

    /// The turn followed by a further `φ` about the vertical (rad, |φ| ≤ π), with `c ≥ 0`
    /// kept: past δ = ±π the pair changes sign, as `sincos(wrap(δ)/2)` does.
    #[inline(always)]
    pub(super) fn turned(self, phi: f64) -> Turn {
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
    pub(super) fn corrected(self, k: f64, f_e: Vec3) -> Turn {
        self.turned(k * self.error(f_e))
    }

    pub(super) fn valid(&self) -> bool {
        (self.c * self.c + self.s * self.s - 1.0).abs() <= 1e-9 && self.c >= 0.0
    }
}

/// The heading error covariance of (H1)-(H4) in the module documentation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct HeadingVariance {
    pub(super) p_ee: f64,
    pub(super) p_eb: f64,
    pub(super) p_bb: f64,
    /// (H5): the low-passed heading innovation ȳ (rad) and the evidence J (rad²).
    pub(super) innov: f64,
    pub(super) evidence: f64,
}

/// (H4): the variance of a heading uniform on the circle.
pub(super) const HEADING_VAR_MAX: f64 = core::f64::consts::PI * core::f64::consts::PI / 3.0;

/// (H1′): the fastest rate a MEMS gyroscope reports of real motion (rad/s): 2000 °/s, the
/// largest full scale of common parts (BMI270, LSM6DSO, MPU-9250, ICM-42688).
pub(super) const PLAUSIBLE_RATE: f64 = 2000.0 * core::f64::consts::PI / 180.0;

/// (H5): c, the share of the innovation evidence J counted in the variance (chosen by
/// cross-validation on BROAD, module documentation).
pub(super) const INNOVATION_SHARE: f64 = 1.0;

/// (H5): g², the gate on ȳ² in units of the innovation variance the model explains,
/// P_ee + σ_v²: (2σ)².
pub(super) const INNOVATION_GATE: f64 = 4.0;

/// (H5): τ_y, the time constant of the innovation low-pass (s; cross-validation).
pub(super) const INNOVATION_TAU: f64 = 4.0;

impl HeadingVariance {
    pub(super) fn start(s: &RobustSettings) -> HeadingVariance {
        HeadingVariance { p_ee: 0.0, p_eb: 0.0, p_bb: s.bias_sigma * s.bias_sigma, innov: 0.0, evidence: 0.0 }
    }

    /// The reported variance: (H5)'s sum, within (H4)'s cap.
    pub(super) fn reported(&self) -> f64 {
        (self.p_ee + INNOVATION_SHARE * self.evidence).min(HEADING_VAR_MAX)
    }

    /// (H5): one innovation y (rad) of an accepted field whose variance is `var_v`, with
    /// the gains of the innovation low-pass `k_y` and of the heading correction `k`.
    pub(super) fn innovation_step(&mut self, y: f64, var_v: f64, k_y: f64, k: f64) {
        let d = y - self.innov;
        // Across ±π the innovation is the same angle: restart there, not average.
        self.innov = if d.abs() > core::f64::consts::PI { y } else { self.innov + d * k_y };
        let y2 = self.innov * self.innov;
        let unexplained = if y2 > INNOVATION_GATE * (self.p_ee + var_v) { y2 } else { 0.0 };
        self.evidence = (self.evidence * (1.0 - k)).max(unexplained);
    }

    /// (H5): the heading was set by a host or from one field: evidence about the one
    /// before it no longer applies.
    pub(super) fn forget_innovation(&mut self) {
        self.innov = 0.0;
        self.evidence = 0.0;
    }

    /// (H1) and (H4).
    pub(super) fn gyro_step(&mut self, dt: f64, turned: f64, s: &RobustSettings) {
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
    pub(super) fn keep_covariance(&mut self) {
        if self.p_eb * self.p_eb > self.p_ee * self.p_bb {
            // max/min, not clamp: no panic on a NaN (readings beyond the runner's bounds
            // fed to the core directly), which the lost-heading test below then resets.
            let bound = (self.p_ee * self.p_bb).sqrt();
            self.p_eb = self.p_eb.max(-bound).min(bound);
        }
    }

    /// New settings: a larger σ_b adds its increase to P_bb, a smaller one caps it (as
    /// the next (H1) step would).
    pub(super) fn configure(&mut self, old: &RobustSettings, new: &RobustSettings) {
        let (before, after) = (old.bias_sigma * old.bias_sigma, new.bias_sigma * new.bias_sigma);
        self.p_bb = (self.p_bb + (after - before).max(0.0)).min(after);
        self.keep_covariance();
    }

    /// (H2).
    pub(super) fn bias_step(&mut self, k_b: f64, sigma_r: f64) {
        self.p_bb = (1.0 - k_b) * (1.0 - k_b) * self.p_bb + k_b * (2.0 - k_b) * sigma_r * sigma_r;
        self.p_eb *= 1.0 - k_b;
    }

    /// (H3), and (H4) for a σ_m set beyond it.
    pub(super) fn heading_step(&mut self, k: f64, sigma_m: f64) {
        self.p_ee = (1.0 - k) * (1.0 - k) * self.p_ee + k * (2.0 - k) * sigma_m * sigma_m;
        self.p_eb *= 1.0 - k;
        if self.p_ee > HEADING_VAR_MAX {
            self.lost();
        }
    }

    /// (H4): the heading is anything.
    pub(super) fn lost(&mut self) {
        self.p_ee = HEADING_VAR_MAX;
        self.p_eb = 0.0;
    }

    /// What (H1)-(H4) can leave: variances in range, and a covariance (|P_eb|² ≤ P_ee P_bb,
    /// to rounding).
    pub(super) fn valid(&self) -> bool {
        use crate::filters::state::holds;
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

    pub(super) fn codec(&mut self, c: &mut dyn Codec) {
        c.f64(&mut self.p_ee);
        c.f64(&mut self.p_eb);
        c.f64(&mut self.p_bb);
        c.f64(&mut self.innov);
        c.f64(&mut self.evidence);
    }
}

impl Robust {
    /// Corrects heading from one magnetometer reading; true when it was used.
    pub(super) fn correct_heading(&mut self, dt: f64, m: Vec3, q_e: Quat) -> bool {
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
        self.ref_norm =
            (self.ref_norm + (f_norm - self.ref_norm) * kr).min(crate::filters::state::holds::MAG_NORM_MAX);
        self.ref_dip += (f_dip - self.ref_dip) * kr;
        true
    }
}
