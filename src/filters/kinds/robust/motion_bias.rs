//! The bias in motion: a Kalman filter on the gyroscope bias b whose measurement is the
//! drift the inclination correction removes.
//!
//! A bias error `b − b̂` (sensor frame) turns the strapdown estimate by `R (b − b̂)` per
//! second in the earth frame, `R` the sensor-to-E′ rotation; the inclination correction
//! then removes its horizontal part. The correction `c` of a step (a rotation about a
//! horizontal axis) thus measures `R b` horizontally: `y = R b̂ − 2 c.xyz / dt`. The
//! correction follows the low-passed accelerometer, so it sees the drift low-passed: the
//! measurement is compared with `LP(R) b̂` and built from `LP(R b̂)`, both through the
//! accelerometer's own low-pass, as VQF does (Laidig and Seel 2023, section on bias
//! estimation in motion):
//!
//! ```text
//! e_xy = −2 c.xy / dt + LP(R b̂)_xy − (LP(R) b̂)_xy,   e_z = −(LP(R) b̂)_z,
//! P⁻ = P + V (each diagonal element up to σ_b²),
//! K = P⁻ LP(R)ᵀ (LP(R) P⁻ LP(R)ᵀ + W)⁻¹,   b̂ += K e,   P = P⁻ − K LP(R) P⁻,
//! ```
//!
//! with `V = σ_w² dt`, σ_w = `bias_walk` (the bias's random walk; by default VQF's
//! forgetting, 0.1 °/s over 100 s; no update while V = 0),
//! `W = diag(w, w, w / 10⁻⁴) (1 + |ω|²/ω_s² + |a_l|²/a_s²)` and `w = σ_m⁴ / V + σ_m²`
//! (the variance that makes σ_m the steady standard deviation of a bias measured at
//! every step), σ_m = `bias_sigma_motion`, |ω|² the mean squared rate and |a_l|² the mean
//! squared linear acceleration (the accelerometer in the almost-inertial frame less its
//! low-pass) since the last update, ω_s = [`SCALE_RATE`] and a_s = [`SCALE_ACCEL`]:
//! while the sensor turns fast its gyroscope's scale and axis errors look like bias to
//! the correction, and so does acceleration the low-pass has not yet averaged out
//! (orient's; VQF has neither term, and the glove and BROAD figures of docs/ACCURACY.md
//! chose them). The filter learns only from two low-pass time constants after a start
//! ([`SETTLED`]). The vertical row has no measurement: its pseudo-measurement of
//! zero, 10⁴ times less certain, only keeps the unobservable direction from wandering.
//! Each component of e and of b̂ is clipped to `bias_limit`, or to the bias's own larger
//! component learned at rest. The filter runs every [`EVERY`] samples on the corrections
//! summed over them (`−Σ 2 c.xy / Σ dt` for the rate), its low-passes and V over their
//! time: the same figures (simulated gloves and BROAD, to the hundredth of a degree) at
//! about a hundred instructions per sample instead of twelve hundred.

use super::*;

/// The rate (rad/s) at which the measurement's variance has doubled: the gyroscope's
/// scale and axis errors turn the estimate in proportion to the rate, which the
/// inclination correction shows as bias while the sensor turns (orient: chosen with
/// `bias_sigma_motion` on BROAD and simulated gloves, docs/ACCURACY.md; 0.2 rad/s is a
/// scale error of 0.3 % at the default σ_m).
const SCALE_RATE: f64 = 0.2;

/// The linear acceleration (m/s², the accelerometer in the almost-inertial frame less its
/// low-pass) at which the measurement's variance has doubled: what the low-pass has not
/// yet averaged out leaks into the correction, which a sensor shaken without turning
/// (a vehicle, a run) would otherwise teach the filter as bias (orient: 4 m/s² at 1 Hz
/// taught 2.5° of tilt in 20 s without it, `rejects_zero_mean_linear_acceleration`).
const SCALE_ACCEL: f64 = 0.25;

/// Bounds of the window's time (s) and squared-rate integral: far beyond any window with
/// accelerometer readings, so that the sums stay finite on a stream without any.
const MAX_T: f64 = 1e12;
const MAX_RATE2: f64 = 1e300;

/// The vertical pseudo-measurement's variance against the horizontal ones' (VQF's
/// biasVerticalForgettingFactor).
const VERTICAL_FACTOR: f64 = 1e-4;

/// The motion bias filter's state: the low-passed rotation (rows) and rotated bias, and
/// the bias covariance.
#[derive(Clone, Debug, Default, PartialEq)]
pub(super) struct MotionBias {
    r_lp: [Butterworth; 3],
    rb_lp: Butterworth,
    pub(super) p: [[f64; 3]; 3],
    /// The corrections of the samples since the last update (twice their vector parts,
    /// earth frame), their time and count, and the integral of the squared rate over
    /// them (the squared rate in units of [`SCALE_RATE`]², plus the squared linear
    /// acceleration in units of [`SCALE_ACCEL`]²).
    sum_c: Vec3,
    t: f64,
    n: u32,
    rate2: f64,
    /// Seconds of samples without an accelerometer reading since the last one.
    gap: f64,
    /// Seconds since the low-passes started (up to [`SETTLED`] τ): the corrections of
    /// the first ones undo the start's error, not a bias's drift.
    age: f64,
}

/// How many low-pass time constants after a start the filter begins to learn: the
/// accelerometer's low-pass averages its readings for one τ and has shed that mean's
/// error by two (a start in motion leaves degrees in it, which the corrections then
/// remove at rates a bias never has).
const SETTLED: f64 = 2.0;

/// Samples per update: the filter runs on the corrections summed over [`EVERY`] samples
/// (the bias moves over tens of seconds; the low-passes' τ is seconds), at an eighth of
/// the cost.
const EVERY: u32 = 8;

type M3 = [[f64; 3]; 3];

/// What a sample tells the filter besides its correction: whether the sensor may teach a
/// bias now (in motion, the low-pass past its warm-up, the estimate on), the de-biased
/// rate's squared norm (rad²/s²) and the linear acceleration's (m²/s⁴, the
/// accelerometer in the almost-inertial frame less its low-pass).
pub(super) struct Activity {
    pub(super) learning: bool,
    pub(super) rate2: f64,
    pub(super) lin2: f64,
}

/// What an update needs of the settings: the accelerometer's low-pass τ (s), the bias
/// before any rest σ_b, the motion estimate's σ_m (rad/s), the clip (rad/s) and the
/// bias's random walk σ_w (rad/s/√s).
pub(super) struct MotionSettings {
    pub(super) tau: f64,
    pub(super) sigma_b: f64,
    pub(super) sigma_m: f64,
    pub(super) limit: f64,
    pub(super) walk: f64,
}

fn mul(a: &M3, b: &M3) -> M3 {
    core::array::from_fn(|i| {
        core::array::from_fn(|j| a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j])
    })
}

fn transpose(a: &M3) -> M3 {
    core::array::from_fn(|i| core::array::from_fn(|j| a[j][i]))
}

fn apply(a: &M3, v: Vec3) -> Vec3 {
    Vec3::new(
        a[0][0] * v.x + a[0][1] * v.y + a[0][2] * v.z,
        a[1][0] * v.x + a[1][1] * v.y + a[1][2] * v.z,
        a[2][0] * v.x + a[2][1] * v.y + a[2][2] * v.z,
    )
}

/// The determinant of a 3×3 matrix.
fn det3(a: &M3) -> f64 {
    a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
        + a[0][1] * (a[1][2] * a[2][0] - a[1][0] * a[2][2])
        + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0])
}

/// The inverse of a symmetric positive definite 3×3 matrix (adjugate over determinant).
fn inverse(a: &M3) -> Option<M3> {
    let c00 = a[1][1] * a[2][2] - a[1][2] * a[2][1];
    let c01 = a[1][2] * a[2][0] - a[1][0] * a[2][2];
    let c02 = a[1][0] * a[2][1] - a[1][1] * a[2][0];
    let det = a[0][0] * c00 + a[0][1] * c01 + a[0][2] * c02;
    if det <= 0.0 || !det.is_finite() {
        return None;
    }
    let d = 1.0 / det;
    Some([
        [c00 * d, (a[0][2] * a[2][1] - a[0][1] * a[2][2]) * d, (a[0][1] * a[1][2] - a[0][2] * a[1][1]) * d],
        [c01 * d, (a[0][0] * a[2][2] - a[0][2] * a[2][0]) * d, (a[0][2] * a[1][0] - a[0][0] * a[1][2]) * d],
        [c02 * d, (a[0][1] * a[2][0] - a[0][0] * a[2][1]) * d, (a[0][0] * a[1][1] - a[0][1] * a[1][0]) * d],
    ])
}

impl MotionBias {
    /// A covariance of σ_b² on each axis.
    pub(super) fn new(sigma_b: f64) -> MotionBias {
        let v = sigma_b * sigma_b;
        MotionBias { p: [[v, 0.0, 0.0], [0.0, v, 0.0], [0.0, 0.0, v]], ..MotionBias::default() }
    }

    /// Starts the low-passes where the accelerometer's starts: from the rotation `q`
    /// (sensor to E′) and the bias `b`; the corrections summed so far are dropped.
    pub(super) fn start(&mut self, q: Quat, b: Vec3) {
        let r = q.to_matrix();
        for (lp, row) in self.r_lp.iter_mut().zip(r) {
            lp.start(Vec3::new(row[0], row[1], row[2]));
        }
        self.rb_lp.start(apply(&r, b));
        self.sum_c = Vec3::ZERO;
        self.t = 0.0;
        self.n = 0;
        self.rate2 = 0.0;
        self.age = 0.0;
    }

    /// A sample without an accelerometer reading (so without a correction): its `dt` and
    /// squared rate count in the window, as the next correction removes its drift too.
    /// (A stream without accelerometer readings would add up forever: the sums stop at
    /// the bounds `valid` holds them to.)
    pub(super) fn elapse(&mut self, dt: f64, rate2: f64) {
        self.gap = (self.gap + dt).min(MAX_T);
        self.t = (self.t + dt).min(MAX_T);
        self.rate2 = (self.rate2 + rate2 * dt / (SCALE_RATE * SCALE_RATE)).min(MAX_RATE2);
    }

    /// The time the accelerometer's reading of this sample stands for: its own `dt` and
    /// that of the samples without one since the last (which it starts over).
    pub(super) fn accel_dt(&mut self, dt: f64) -> f64 {
        let held = self.gap + dt;
        self.gap = 0.0;
        held
    }

    /// A rest step of gain `k_b` towards a bias known to σ_r: the covariance as the
    /// heading model's (H2), on every axis.
    pub(super) fn rest_step(&mut self, k_b: f64, sigma_r: f64) {
        let keep = (1.0 - k_b) * (1.0 - k_b);
        let add = k_b * (2.0 - k_b) * sigma_r * sigma_r;
        for (i, row) in self.p.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                *v = *v * keep + if i == j { add } else { 0.0 };
            }
        }
    }

    /// One sample's correction `c` (the inclination's, just made), with `q` the rotation
    /// (sensor to E′) before it, `b` the bias and what the sample tells (`now`): every
    /// [`EVERY`] samples the filter's
    /// update, which gives the new bias, unless the sensor was not `learning` (then only
    /// the low-passes and the covariance move) or the update is degenerate.
    pub(super) fn update(
        &mut self,
        dt: f64,
        q: Quat,
        c: Quat,
        b: Vec3,
        m: &MotionSettings,
        now: Activity,
    ) -> Option<Vec3> {
        let Activity { learning, rate2, lin2 } = now;
        self.rate2 = (self.rate2
            + (rate2 / (SCALE_RATE * SCALE_RATE) + lin2 / (SCALE_ACCEL * SCALE_ACCEL)) * dt)
            .min(MAX_RATE2);
        self.sum_c = self.sum_c + c.vector() * 2.0;
        self.t = (self.t + dt).min(MAX_T);
        self.n += 1;
        if self.n < EVERY {
            return None;
        }
        let (dt, sum_c) = (self.t, self.sum_c);
        // The measurement's variance grows with the window's mean squared rate and linear
        // acceleration.
        let scale = 1.0 + self.rate2 / dt;
        self.rate2 = 0.0;
        self.sum_c = Vec3::ZERO;
        self.t = 0.0;
        self.n = 0;
        let (tau, sigma_b, sigma_m, limit, walk) = (m.tau, m.sigma_b, m.sigma_m, m.limit, m.walk);
        let r = q.to_matrix();
        let r_lp: M3 = core::array::from_fn(|i| {
            let v = self.r_lp[i].filter(dt, tau, Vec3::new(r[i][0], r[i][1], r[i][2]));
            [v.x, v.y, v.z]
        });
        let rb_lp = self.rb_lp.filter(dt, tau, apply(&r, b));
        let v = walk * walk * dt;
        for i in 0..3 {
            if self.p[i][i] < sigma_b * sigma_b {
                self.p[i][i] = (self.p[i][i] + v).min(sigma_b * sigma_b);
            }
        }
        self.age = (self.age + dt).min(SETTLED * tau);
        // A bias that never moves (V = 0, or a walk whose square underflows) is learned at
        // rest only: W's σ_m⁴ / V would be infinite.
        if !learning || self.age < SETTLED * tau || v <= 0.0 {
            return None;
        }
        let pm = sigma_m * sigma_m;
        let w = (pm * pm / v + pm) * scale;
        let pred = apply(&r_lp, b);
        let clip = |x: f64| x.clamp(-limit, limit);
        let e = Vec3::new(
            clip(-sum_c.x / dt + rb_lp.x - pred.x),
            clip(-sum_c.y / dt + rb_lp.y - pred.y),
            clip(-pred.z),
        );
        // K = P Rᵀ (R P Rᵀ + W)⁻¹.
        let prt = mul(&self.p, &transpose(&r_lp));
        let mut s = mul(&r_lp, &prt);
        s[0][0] += w;
        s[1][1] += w;
        s[2][2] += w / VERTICAL_FACTOR;
        let k = mul(&prt, &inverse(&s)?);
        let nb = b + apply(&k, e);
        // P = P − K R P.
        let krp = mul(&k, &mul(&r_lp, &self.p));
        let np: M3 = core::array::from_fn(|i| core::array::from_fn(|j| self.p[i][j] - krp[i][j]));
        // Only a finite update is taken: low-passes at the ends of their range (a state
        // loaded from a blob) can overflow the products; the next update starts afresh.
        if !(nb.is_finite() && np.iter().flatten().all(|v| v.is_finite())) {
            return None;
        }
        // Symmetric, as rounding leaves it only nearly, with a diagonal that is not negative
        // and correlations within ±1 (rounding can leave a variance near zero, σ_b = 0
        // say, under the square of its covariances).
        let d: [f64; 3] = core::array::from_fn(|i| np[i][i].max(0.0));
        self.p = core::array::from_fn(|i| {
            core::array::from_fn(|j| {
                if i == j {
                    d[i]
                } else {
                    let bound = (d[i] * d[j]).sqrt();
                    (0.5 * (np[i][j] + np[j][i])).clamp(-bound, bound)
                }
            })
        });
        Some(Vec3::new(clip(nb.x), clip(nb.y), clip(nb.z)))
    }

    /// A forged state made one `valid` accepts: the low-passes' coefficients those of
    /// `dt` and `tau`, the covariance a covariance (its diagonal kept, each correlation in
    /// [0, 1) from `u`), the sample count under [`EVERY`].
    #[cfg(test)]
    pub(super) fn make_consistent(&mut self, dt: f64, tau: f64, u: &mut dyn FnMut() -> f64) {
        for lp in self.r_lp.iter_mut().chain([&mut self.rb_lp]) {
            lp.coefficients(dt, tau);
        }
        for i in 0..3 {
            self.p[i][i] = self.p[i][i].abs();
        }
        for i in 0..3 {
            for j in 0..i {
                let c = (self.p[i][i] * self.p[j][j]).sqrt() * (0.5 * (u() + 1.0)) * 0.5;
                self.p[i][j] = c;
                self.p[j][i] = c;
            }
        }
        self.n %= EVERY;
    }

    /// P's correlations (0 where a variance is 0, and so its covariances).
    fn correlations(&self) -> M3 {
        let d: [f64; 3] = core::array::from_fn(|i| self.p[i][i].max(0.0).sqrt());
        core::array::from_fn(|i| {
            core::array::from_fn(|j| {
                let n = d[i] * d[j];
                if i == j {
                    1.0
                } else if n > 0.0 {
                    self.p[i][j] / n
                } else {
                    0.0
                }
            })
        })
    }

    pub(super) fn valid(&self) -> bool {
        self.r_lp.iter().all(Butterworth::valid)
            && self.rb_lp.valid()
            && self.p.iter().flatten().all(|v| v.is_finite())
            && (0..3).all(|i| self.p[i][i] >= 0.0)
            // A covariance's off-diagonal elements: |P_ij| ≤ √(P_ii P_jj).
            && (0..3).all(|i| (0..3).all(|j| self.p[i][j].powi(2) <= self.p[i][i] * self.p[j][j] * (1.0 + 1e-9)))
            // And positive semi-definite as a whole (the pairwise bound allows, say,
            // correlations 1, 1, −1, whose determinant is negative): the correlations'
            // determinant ≥ 0 to rounding.
            && det3(&self.correlations()) >= -1e-9
            && self.sum_c.is_finite()
            && (0.0..=MAX_T).contains(&self.t)
            && self.n < EVERY
            && (0.0..=MAX_RATE2).contains(&self.rate2)
            && (0.0..=1e6).contains(&self.age)
            && (0.0..=MAX_T).contains(&self.gap)
    }

    pub(super) fn codec(&mut self, c: &mut dyn Codec) {
        for lp in &mut self.r_lp {
            lp.codec(c);
        }
        self.rb_lp.codec(c);
        for v in self.p.iter_mut().flatten() {
            c.f64(v);
        }
        c.vec3(&mut self.sum_c);
        c.f64(&mut self.t);
        c.u32(&mut self.n);
        c.f64(&mut self.rate2);
        c.f64(&mut self.age);
        c.f64(&mut self.gap);
    }
}
