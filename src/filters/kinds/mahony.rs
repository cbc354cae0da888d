//! Mahony's nonlinear complementary filter ("explicit complementary filter"), IMU and MARG.
//!
//! Source: R. Mahony, T. Hamel, J.-M. Pflimlin, "Nonlinear Complementary Filters on the
//! Special Orthogonal Group", IEEE TAC 53(5), 2008 (reference \[14\] of the McGinnis paper;
//! the baseline of the GMVDK paper's comparison). With measured directions `v_i` and
//! their estimates `v̂_i` in the sensor frame,
//!
//! ```text
//! ω_mes = Σ v_i × v̂_i                 (correction, rad)
//! ḃ     = −k_I ω_mes                  (bias; orient reports b)
//! q̇     = ½ q ⊗ (ω_y − b + k_P ω_mes)
//! ```
//!
//! The directions are gravity's reaction `â` against `v̂ = R(q)ᵀ e_z` and, with a
//! magnetometer, `m̂` against the estimated field `R(q)ᵀ [0 b_y b_z]`, whose reference is
//! taken from the measurement itself as in Madgwick's (31)-(32), so that magnetic
//! inclination errors cannot tilt the estimate. The native frame is magnetic
//! East-North-Up (Madgwick's `b_x`, north, is `b_y` here): orient's default frame, so
//! that the default output needs no rotation. The equations do not depend on that choice
//! (it turns the earth frame about the vertical) beyond rounding. Integration is first
//! order followed by normalisation, as in the widely used implementation that produced
//! the BROAD baseline numbers.

use crate::filters::kinds::rest::RestBias;
use crate::filters::params::settings;
use crate::filters::pipeline::estimator::Step;
use crate::filters::pipeline::sample::{Checked, Usual};
use crate::math::{inv_sqrt_fast, inv_sqrt_in_range, Quat, Vec3};

settings! {
    /// Mahony's settings.
    pub struct MahonySettings {
        kp: f64 = MAHONY_KP 16 {
            unit: "1/s",
            default: 0.5,
            min: 0.0,
            max: 1000.0,
            zero_off: false,
            doc: "Proportional gain on the direction error (Mahony 2008); default 0.5 as in the \
                 GMVDK paper's comparison and BROAD's baseline.",
        },
        ki: f64 = MAHONY_KI 17 {
            unit: "1/s^2",
            default: 0.0,
            min: 0.0,
            max: 1000.0,
            zero_off: false,
            doc: "Integral gain for the gyroscope bias (Mahony 2008); default 0 (no bias \
                 estimation) as in the GMVDK paper's comparison. Set to 0 with rest_bias_tau \
                 also 0, the bias estimate is dropped.",
        },
        rest_bias_tau: f64 = MAHONY_REST_BIAS_TAU 18 {
            unit: "s",
            default: 0.0,
            min: 1e-3,
            max: 3600.0,
            zero_off: true,
            doc: "orient option: at detected rest (2 deg/s, 0.5 m/s^2, 0.5 deg tilt for 1.5 s) the \
                 bias b follows the low-passed gyro with this time constant; default 0 = off \
                 (Mahony's filter).",
        },
    }
}

/// Mahony's filter: orientation (East-North-Up) and gyroscope bias.
#[derive(Clone, Debug, PartialEq)]
pub struct Mahony {
    pub settings: MahonySettings,
    q: Quat,
    bias: Vec3,
    rest: RestBias,
}

impl Mahony {
    pub fn new(settings: MahonySettings) -> Mahony {
        let mut rest = RestBias::default();
        rest.prepare(settings.rest_bias_tau > 0.0);
        Mahony { settings, q: Quat::IDENTITY, bias: Vec3::ZERO, rest }
    }

    pub fn quaternion(&self) -> Quat {
        self.q
    }

    pub fn set_quaternion(&mut self, q: Quat) {
        self.q = q;
    }

    /// After a gap: the re-acquired estimate, rest detection started over; the bias b
    /// (the integral term) is kept, but for the rest watch's re-acquisition of a still
    /// sensor, where a bias the filter learns (`ki` or `rest_bias_tau` set) or still
    /// subtracts (learned before those were set to 0) is the gyroscope's reading: an
    /// integral wound up while the estimate was off would turn it away again.
    pub(crate) fn reacquire(&mut self, r: &crate::filters::pipeline::estimator::Reacquisition) -> bool {
        let (q, used_mag) = r.plain();
        self.q = q;
        // A bias it learns, or one kept from settings that learned it (k_I set to 0
        // freezes b, still subtracted).
        if let Some(g) =
            r.still.filter(|_| self.ki() || self.settings.rest_bias_tau > 0.0 || self.bias != Vec3::ZERO)
        {
            self.bias = g;
        }
        self.rest.restart();
        used_mag
    }

    pub(crate) fn codec(&mut self, c: &mut dyn crate::filters::state::Codec) {
        c.quat(&mut self.q);
        c.vec3(&mut self.bias);
        self.rest.codec(c);
    }

    /// Values an update could leave (see `filters::holds`).
    pub(crate) fn valid(&self) -> bool {
        crate::filters::state::holds::unit(self.q)
            && crate::filters::state::holds::rate(self.bias)
            && self.rest.valid()
    }

    /// True when the last sample counted as rest (only tracked with `rest_bias_tau` set).
    pub fn at_rest(&self) -> bool {
        self.rest.at_rest()
    }

    /// The bias estimate b (rad/s), subtracted from the gyroscope.
    pub fn bias(&self) -> Vec3 {
        self.bias
    }

    /// The correction term `ω_mes = â × v̂ (+ m̂ × ŵ)` in the sensor frame, and whether
    /// the magnetometer contributed.
    pub fn correction(q: Quat, accel: Vec3, mag: Option<Vec3>) -> (Vec3, bool) {
        Mahony::correction_of_units(q, accel.normalized(), mag.map(Vec3::normalized))
    }

    /// [`Mahony::correction`] from the normalised readings `â` and `m̂`.
    #[inline(always)]
    fn correction_of_units(q: Quat, a: Vec3, m: Option<Vec3>) -> (Vec3, bool) {
        // The rows of R(q): v̂ is the third, the earth's z axis in the sensor frame.
        let [r0, r1, up] = q.rows();
        if let Some(m) = m {
            // h = q ⊗ m̂ ⊗ q* = R m̂; b = [0, √(h_x² + h_y²), h_z] keeps the field's dip
            // and drops its heading (north is y); ŵ = q* ⊗ b ⊗ q = Rᵀ b = b_y r1 + b_z r2.
            let h = Vec3::new(r0.dot(m), r1.dot(m), up.dot(m));
            let by = (h.x * h.x + h.y * h.y).sqrt();
            if by > 0.0 {
                // â × v̂ + m̂ × ŵ = â × r2 + b_y (m̂ × r1) + b_z (m̂ × r2)
                //               = (â + b_z m̂) × r2 + b_y (m̂ × r1),
                // one cross product fewer; m̂ × r1 does not wait for the square root.
                return ((a + m * h.z).cross(up) + m.cross(r1) * by, true);
            }
        }
        (a.cross(up), false)
    }

    #[inline(always)]
    pub fn update(&mut self, dt: f64, gyro: Vec3, accel: Option<Vec3>, mag: Option<Vec3>) -> Option<Step> {
        if self.settings.rest_bias_tau > 0.0 {
            return self.update_with_rest_bias(dt, gyro, accel, mag);
        }
        match (accel, mag) {
            (Some(a), None) => {
                self.update_with::<false, false>(dt, gyro, a.normalized(), Vec3::ZERO, self.ki())
            }
            (Some(a), Some(m)) => {
                self.update_with::<true, false>(dt, gyro, a.normalized(), m.normalized(), self.ki())
            }
            (None, _) => self.update_gyro_only(dt, gyro, mag),
        }
    }

    /// The rest-bias option off: the settings [`Mahony::update_usual`] is for.
    pub(crate) fn usual_settings(&self) -> bool {
        self.settings.rest_bias_tau == 0.0
    }

    /// [`Mahony::update`]'s usual case, which calls no function, for the
    /// [`Mahony::usual_settings`] with an accelerometer reading (the new estimate's squared
    /// norm is then in [`crate::math::inv_sqrt`]'s fast range: see [`Mahony::step`]). The
    /// same result, or `None` with nothing changed otherwise.
    #[inline(always)]
    pub(crate) fn update_usual(&mut self, s: &Usual) -> Option<u32> {
        debug_assert!(self.usual_settings());
        // The flags each case leaves are computed in its copy, before the copies join.
        match (s.accel, s.mag) {
            // Without a magnetometer, one copy with the integral term and one without (the
            // default), with k_I tested once, here.
            (Some(a), None) if self.ki() => self.update_usual_imu(s.dt, s.gyro, a.unit(), true),
            (Some(a), None) => self.update_usual_imu(s.dt, s.gyro, a.unit(), false),
            (Some(a), Some(m)) => {
                let (a, m) = Checked::heading_units(a, m)?;
                self.update_with::<true, true>(s.dt, s.gyro, a, m, self.ki()).map(|st| st.flags(true, true))
            }
            (None, _) => None,
        }
    }

    /// [`Mahony::update_usual`] without a magnetometer reading, with the integral term on
    /// or off (`ki`, a constant in each copy).
    #[inline(always)]
    fn update_usual_imu(&mut self, dt: f64, gyro: Vec3, a: Vec3, ki: bool) -> Option<u32> {
        self.update_with::<false, true>(dt, gyro, a, Vec3::ZERO, ki).map(|st| st.flags(true, false))
    }

    /// Whether the integral term is on (k_I > 0).
    #[inline(always)]
    fn ki(&self) -> bool {
        self.settings.ki > 0.0
    }

    /// The update without the rest-bias option, with the normalised accelerometer reading
    /// `â` and with (`MAG`) or without a magnetometer reading `m̂`: one copy per case,
    /// each with its step and correction inlined, inlined in turn into the kind's update
    /// function (`Runner::update_outline`, the `USUAL` copies; the others into
    /// `Runner::update_general`). `ki`: the integral term is on (k_I > 0), a constant in
    /// the usual IMU copies. `USUAL`: see [`Mahony::step`].
    #[inline(always)]
    fn update_with<const MAG: bool, const USUAL: bool>(
        &mut self,
        dt: f64,
        gyro: Vec3,
        a: Vec3,
        m: Vec3,
        ki: bool,
    ) -> Option<Step> {
        let (q, bias, step) = self.step::<USUAL>(self.bias, dt, gyro, Some(a), MAG.then_some(m), ki)?;
        self.q = q;
        // Without the integral term (k_I = 0, the default) the bias stays as it was.
        if ki {
            self.bias = bias;
        }
        Some(step)
    }

    /// The update without the rest-bias option and without an accelerometer reading (the
    /// bias does not change).
    #[inline(never)]
    fn update_gyro_only(&mut self, dt: f64, gyro: Vec3, mag: Option<Vec3>) -> Option<Step> {
        let (q, _, step) = self.step::<false>(self.bias, dt, gyro, None, mag.map(Vec3::normalized), false)?;
        self.q = q;
        Some(step)
    }

    /// [`Mahony::update`] with the rest-bias option: the rest detector's state changes
    /// only when the step succeeds. Kept apart so the plain update copies no detector.
    #[inline(never)]
    fn update_with_rest_bias(
        &mut self,
        dt: f64,
        gyro: Vec3,
        accel: Option<Vec3>,
        mag: Option<Vec3>,
    ) -> Option<Step> {
        let (detector, bias) = self.rest.update(dt, gyro, accel, self.settings.rest_bias_tau, self.bias);
        if !bias.is_finite() {
            return None;
        }
        let (a, m) = (accel.map(Vec3::normalized), mag.map(Vec3::normalized));
        let (q, bias, step) = self.step::<false>(bias, dt, gyro, a, m, self.ki())?;
        self.q = q;
        self.bias = bias;
        self.rest.commit(detector);
        Some(step)
    }

    /// One step from the current estimate with gyro bias `bias` and the normalised
    /// readings `â` and `m̂`, with the integral term when `ki` (k_I > 0): the new estimate
    /// and bias, or `None` when either is not finite. `USUAL`: the usual case, a sample
    /// the quick check accepted, which calls no function: the new estimate's squared norm
    /// is in [`crate::math::inv_sqrt`]'s fast range without a test (the bounds are below).
    #[inline(always)]
    fn step<const USUAL: bool>(
        &self,
        mut bias: Vec3,
        dt: f64,
        gyro: Vec3,
        a: Option<Vec3>,
        m: Option<Vec3>,
        ki: bool,
    ) -> Option<(Quat, Vec3, Step)> {
        let mut step = Step::default();
        let mut omega = gyro - bias;
        if let Some(a) = a {
            let (e, used_mag) = Mahony::correction_of_units(self.q, a, m);
            step.used_accel = true;
            step.used_mag = used_mag;
            if ki {
                bias = bias - e * (self.settings.ki * dt);
                if !bias.is_finite() {
                    return None;
                }
                omega = gyro - bias;
            }
            omega = omega + e * self.settings.kp;
        }
        let h = 0.5 * dt;
        // q + h q⊗ω. |q + h q⊗ω|² = |q|² (1 + h²|ω|²), as q⊗ω is orthogonal to q: the norm
        // is known without waiting for the new quaternion.
        let q = self.q.plus_mul_pure_scaled(omega, h);
        let n2 = self.q.norm_squared() * (1.0 + h * h * omega.norm_squared());
        // With n2 in inv_sqrt's fast range, h|ω| < 1e150 and the unit q bound every
        // component of the new q, so it and its scaled copy are finite (the bias was
        // tested where it changed). Otherwise `normalized_with`, which tests the result.
        //
        // In the usual case n2 needs no test: |q|² is 1 to rounding, and 1 + h²|ω|² is at
        // least 1 and far below 1e300. h ≤ 5e5 s; |ω| is under 2e4 rad/s for the reading,
        // 2e3 for k_P e (|e| ≤ 2, k_P ≤ 1000) and the bias's bound, 1e5 where it is
        // loaded, plus at most 2 k_I dt < 2e9 rad/s per update with k_I > 0: h|ω| would
        // need more than 1e130 updates to reach 1e150.
        let q = if USUAL {
            debug_assert!(n2 > 0.5 && n2 < 1e300, "{n2}");
            q.scale(inv_sqrt_in_range(n2))
        } else {
            match inv_sqrt_fast(n2) {
                Some(r) => q.scale(r),
                None => q.normalized_with(n2)?,
            }
        };
        Some((q, bias, step))
    }
}

#[cfg(test)]
mod tests;

/// The common lifecycle's view of this kind (see [`crate::filters::pipeline::estimator::Estimator`]).
mod estimator_impl {
    use super::*;
    use crate::filters::diag;
    use crate::filters::pipeline::estimator::estimator;
    use crate::filters::Diagnostics;

    estimator!(impl for Mahony { settings: MahonySettings, native: Enu, own_startup: false, diagnostics: GYRO_BIAS | REST, usual: true } {
        fn configure(&mut self, settings: MahonySettings) {
            self.settings = settings;
            // With neither k_I nor the rest learner, b is no estimate any more: dropped, or a
            // bias learned (or wound up) before would be subtracted for good.
            if settings.ki == 0.0 && settings.rest_bias_tau == 0.0 {
                self.bias = Vec3::ZERO;
            }
            self.rest.prepare(settings.rest_bias_tau > 0.0);
        }

        fn restart(&mut self, settings: MahonySettings) {
            // As new(settings), keeping the detector's box: no allocation.
            self.settings = settings;
            self.q = Quat::IDENTITY;
            self.bias = Vec3::ZERO;
            self.rest.restart();
            self.rest.prepare(settings.rest_bias_tau > 0.0);
        }

        #[inline(always)]
        fn update(&mut self, dt: f64, gyro: Vec3, accel: Option<Vec3>, mag: Option<Vec3>) -> Option<Step> {
            Mahony::update(self, dt, gyro, accel, mag)
        }

        fn fields(&self) -> u32 {
            if self.settings.rest_bias_tau > 0.0 {
                diag::GYRO_BIAS | diag::REST
            } else {
                diag::GYRO_BIAS
            }
        }

        fn diagnose(&self, d: &mut Diagnostics) {
            d.gyro_bias = self.bias();
            d.rest = if Mahony::at_rest(self) { 1.0 } else { 0.0 };
        }

        fn at_rest(&self) -> bool {
            self.settings.rest_bias_tau > 0.0 && Mahony::at_rest(self)
        }

        fn learns_bias_in_motion(&self) -> bool {
            // The integral term; the rest learner learns at rest only.
            self.settings.ki > 0.0
        }
    });
}
