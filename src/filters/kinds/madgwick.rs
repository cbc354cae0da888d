//! Madgwick's gradient-descent orientation filter, IMU and MARG, with magnetic distortion
//! compensation.
//!
//! Source: S. O. H. Madgwick, "An efficient orientation filter for inertial and
//! inertial/magnetic sensor arrays", 2010 (`shared/papers/madgwick-2010-gradient-descent.txt`).
//! Equation numbers below are the paper's.
//!
//! The paper writes the orientation as `ᴱₛq̂ = [q1 q2 q3 q4]` with the objective
//! `f = q* ⊗ d ⊗ q − s` (6): a field `d` known in the earth frame is seen in the
//! sensor as `s = q* ⊗ d ⊗ q`. That is orient's convention (`v_earth = q ⊗ v_body ⊗ q*`)
//! with `q1..q4 = w, x, y, z`. The earth frame of the equations has gravity's reaction
//! along +z (10) and the horizontal field along +x (14): magnetic North-West-Up, the
//! filter's native frame; [`crate::Filter`] rotates it into the configured frame.
//!
//! Choices where the text is ambiguous:
//! - (16) and (17) multiply the reference field by 2 (`2 b_x`, `2 b_z`); the widely copied
//!   2012 C code uses `b` where these need `2b`. This follows the paper.
//! - (17) is damaged in the extracted text (printed as a 6×2 block). It is read as the
//!   3×4 Jacobian of (16), which the unit tests check against a finite difference.
//! - (31)-(32) use the previous estimate `q̂_est,t−1` and the normalised magnetometer, so
//!   `|b| = 1`. When the field has no horizontal component (`b_x = 0`, magnetometer
//!   parallel to gravity) (18) has no unique minimum; that step uses the IMU form (12)-(13).
//! - A step without an accelerometer integrates the gyroscope alone: (29) with (30)'s
//!   correction term absent.
//! - β for a step follows the sensors used in it: `beta_imu` for (12)-(13), `beta_marg`
//!   for (18)-(19), the two values the paper found optimal (section V).

use crate::filters::kinds::rest::RestBias;
use crate::filters::params::settings;
use crate::filters::pipeline::estimator::Step;
use crate::filters::pipeline::sample::{Checked, Usual};
use crate::math::lanes::F64x2 as Lane;
use crate::math::lanes::Real;
use crate::math::{inv_sqrt, inv_sqrt_fast, inv_sqrt_fast_bounded, Quat, Vec3};

/// A quaternion's components `[q1 q2 q3 q4]` (w, x, y, z), of one filter (`T = f64`) or
/// of two ([`Lane`], one filter per lane): the update below is written once, on these,
/// for both (see [`Real`]).
type Q<T> = [T; 4];
/// A vector's components `[x y z]`, as [`Q`].
type V<T> = [T; 3];

#[inline(always)]
fn q_of(q: Quat) -> Q<f64> {
    [q.w, q.x, q.y, q.z]
}

#[inline(always)]
fn v_of(v: Vec3) -> V<f64> {
    [v.x, v.y, v.z]
}

#[inline(always)]
fn quat(q: Q<f64>) -> Quat {
    Quat::new(q[0], q[1], q[2], q[3])
}

/// [`Quat::dot`]: `(a1 b1 + a2 b2) + (a3 b3 + a4 b4)`.
#[inline(always)]
fn dot_of<T: Real>(a: Q<T>, b: Q<T>) -> T {
    (a[0] * b[0] + a[1] * b[1]) + (a[2] * b[2] + a[3] * b[3])
}

/// [`Vec3::cross`].
#[inline(always)]
fn cross_of<T: Real>(u: V<T>, v: V<T>) -> V<T> {
    [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
}

settings! {
    /// Madgwick's settings, in user units.
    pub struct MadgwickSettings {
        beta_imu: f64 = MADGWICK_BETA_IMU 8 {
            unit: "rad/s",
            default: 0.041,
            min: 0.0,
            max: 100.0,
            zero_off: false,
            doc: "Gradient step beta for steps without magnetometer, eq. (30); default 0.041 \
                 (paper: Madgwick 2010, section V, optimum of the IMU implementation). \
                 beta = sqrt(3/4) * max gyro error, eq. (33). The step follows the normalised \
                 gradient, so the estimate wanders by about beta * dt rad RMS at rest (0.6 deg at \
                 beta 1 and 100 Hz).",
        },
        beta_marg: f64 = MADGWICK_BETA_MARG 9 {
            unit: "rad/s",
            default: 0.041,
            min: 0.0,
            max: 100.0,
            zero_off: false,
            doc: "Gradient step beta for steps with magnetometer, eq. (30); default 0.041, the \
                 paper's IMU optimum (section V). The paper's MARG optimum, 0.033, was found for \
                 its own sensor (beta scales with gyro error, eq. (33)); on BROAD it scores 7.79 \
                 deg against 7.22 for 0.041, which is also the Python ahrs reference's value. \
                 At rest the estimate wanders by about beta * dt rad RMS, as with beta_imu.",
        },
        rest_bias_tau: f64 = MADGWICK_REST_BIAS_TAU 10 {
            unit: "s",
            default: 0.0,
            min: 1e-3,
            max: 3600.0,
            zero_off: true,
            doc: "orient option: learn the gyro bias at detected rest (2 deg/s, 0.5 m/s^2, 0.5 deg \
                 tilt for 1.5 s) with this time constant and subtract it; default 0 = off (the \
                 paper has no bias estimate in this form).",
        },
    }
}

/// β from the maximum gyroscope measurement error `ω̃_max` (rad/s) of each axis, eq. (33):
/// `β = ‖½ q̂ ⊗ [0 ω̃ ω̃ ω̃]‖ = √(3/4) ω̃_max`.
pub fn beta_from_gyro_error(gyro_error_max: f64) -> f64 {
    (0.75f64).sqrt() * gyro_error_max
}

/// Objective function for gravity, eq. (12): `f_g = q* ⊗ [0 0 0 1] ⊗ q − â`.
#[inline]
pub fn objective_g(q: Quat, a: Vec3) -> [f64; 3] {
    objective_g_of(q_of(q), v_of(a))
}

#[inline(always)]
fn objective_g_of<T: Real>(q: Q<T>, a: V<T>) -> V<T> {
    let [q1, q2, q3, q4] = q;
    let k = T::of;
    [
        k(2.0) * (q2 * q4 - q1 * q3) - a[0],
        k(2.0) * (q1 * q2 + q3 * q4) - a[1],
        k(2.0) * (k(0.5) - q2 * q2 - q3 * q3) - a[2],
    ]
}

/// Jacobian of (12), eq. (13): rows are the components of `f_g`, columns `q1..q4`.
#[inline]
pub fn jacobian_g(q: Quat) -> [[f64; 4]; 3] {
    let Quat { w: q1, x: q2, y: q3, z: q4 } = q;
    [
        [-2.0 * q3, 2.0 * q4, -2.0 * q1, 2.0 * q2],
        [2.0 * q2, 2.0 * q1, 2.0 * q4, 2.0 * q3],
        [0.0, -4.0 * q2, -4.0 * q3, 0.0],
    ]
}

/// Objective function for the magnetic field, eq. (16), with `ᴱb̂ = [0 b_x 0 b_z]` (14).
#[inline]
pub fn objective_b(q: Quat, bx: f64, bz: f64, m: Vec3) -> [f64; 3] {
    objective_b_of(q_of(q), bx, bz, v_of(m))
}

#[inline(always)]
fn objective_b_of<T: Real>(q: Q<T>, bx: T, bz: T, m: V<T>) -> V<T> {
    let [q1, q2, q3, q4] = q;
    let k = T::of;
    [
        k(2.0) * bx * (k(0.5) - q3 * q3 - q4 * q4) + k(2.0) * bz * (q2 * q4 - q1 * q3) - m[0],
        k(2.0) * bx * (q2 * q3 - q1 * q4) + k(2.0) * bz * (q1 * q2 + q3 * q4) - m[1],
        k(2.0) * bx * (q1 * q3 + q2 * q4) + k(2.0) * bz * (k(0.5) - q2 * q2 - q3 * q3) - m[2],
    ]
}

/// Jacobian of (16), eq. (17): rows are the components of `f_b`, columns `q1..q4`.
#[inline]
pub fn jacobian_b(q: Quat, bx: f64, bz: f64) -> [[f64; 4]; 3] {
    let Quat { w: q1, x: q2, y: q3, z: q4 } = q;
    [
        [-2.0 * bz * q3, 2.0 * bz * q4, -4.0 * bx * q3 - 2.0 * bz * q1, -4.0 * bx * q4 + 2.0 * bz * q2],
        [
            -2.0 * bx * q4 + 2.0 * bz * q2,
            2.0 * bx * q3 + 2.0 * bz * q1,
            2.0 * bx * q2 + 2.0 * bz * q4,
            -2.0 * bx * q1 + 2.0 * bz * q3,
        ],
        [2.0 * bx * q3, 2.0 * bx * q4 - 4.0 * bz * q2, 2.0 * bx * q1 - 4.0 * bz * q3, 2.0 * bx * q2],
    ]
}

/// Reference direction of the field, eqs. (31)-(32): the measured field `m̂` rotated into
/// the earth frame by the previous estimate, `ᴱh = q ⊗ m̂ ⊗ q*`, then
/// `b_x = √(h_x² + h_y²)`, `b_z = h_z`.
#[inline]
pub fn reference_field(q: Quat, m: Vec3) -> (f64, f64) {
    reference_field_of(q_of(q), v_of(m))
}

/// (31)-(32) with `q ⊗ m̂ ⊗ q*` as [`Quat::rotate`] computes it: `m̂ + q1 t + u × t`,
/// `u = [q2 q3 q4]`, `t = 2 u × m̂`.
#[inline(always)]
fn reference_field_of<T: Real>(q: Q<T>, m: V<T>) -> (T, T) {
    let u = [q[1], q[2], q[3]];
    let t = cross_of(u, m).map(|c| c * T::of(2.0));
    let ut = cross_of(u, t);
    let h: V<T> = core::array::from_fn(|i| m[i] + t[i] * q[0] + ut[i]);
    ((h[0] * h[0] + h[1] * h[1]).sqrt(), h[2])
}

/// `Jᵀ f` for a 3×4 Jacobian and a 3-vector, as a quaternion (eq. (8)).
#[inline]
pub fn jt_f(j: &[[f64; 4]; 3], f: &[f64; 3]) -> Quat {
    quat(jt_f_of(j, f))
}

#[inline(always)]
fn jt_f_of<T: Real>(j: &[[T; 4]; 3], f: &V<T>) -> Q<T> {
    core::array::from_fn(|c| j[0][c] * f[0] + j[1][c] * f[1] + j[2][c] * f[2])
}

/// `½ ∇f` for the IMU, eq. (21) first case: `½ J_gᵀ f_g` with (13) halved, whose rows
/// are `[−q3 q4 −q1 q2]`, `[q2 q1 q4 q3]`, `[0 −2q2 −2q3 0]`.
///
/// Why half: (30) uses `∇f` only through its direction `∇f / ‖∇f‖`, and a power of two
/// scales every product and sum without rounding, so `½ ∇f` gives the update the same
/// bits while the 2s and 4s of (13) need no multiplications (a test checks it bit for bit
/// against [`jt_f`] of [`jacobian_g`] and [`objective_g`]).
#[inline]
pub fn half_gradient_imu(q: Quat, a: Vec3) -> Quat {
    quat(half_gradient_imu_of(q_of(q), v_of(a)))
}

#[inline(always)]
fn half_gradient_imu_of<T: Real>(q: Q<T>, a: V<T>) -> Q<T> {
    let [q1, q2, q3, q4] = q;
    let [f1, f2, f3] = objective_g_of(q, a);
    let two = T::of(2.0);
    [
        q2 * f2 - q3 * f1,
        (q4 * f1 + q1 * f2) - two * q2 * f3,
        (q4 * f2 - q1 * f1) - two * q3 * f3,
        q2 * f1 + q3 * f2,
    ]
}

/// (17) halved: `½ J_b` (see [`half_gradient_imu`] for why half).
#[inline]
pub fn half_jacobian_b(q: Quat, bx: f64, bz: f64) -> [[f64; 4]; 3] {
    half_jacobian_b_of(q_of(q), bx, bz)
}

#[inline(always)]
fn half_jacobian_b_of<T: Real>(q: Q<T>, bx: T, bz: T) -> [[T; 4]; 3] {
    let [q1, q2, q3, q4] = q;
    let two = T::of(2.0);
    [
        [-bz * q3, bz * q4, -two * bx * q3 - bz * q1, -two * bx * q4 + bz * q2],
        [-bx * q4 + bz * q2, bx * q3 + bz * q1, bx * q2 + bz * q4, -bx * q1 + bz * q3],
        [bx * q3, bx * q4 - two * bz * q2, bx * q1 - two * bz * q3, bx * q2],
    ]
}

/// `½ ∇f` for MARG, eqs. (18), (19), (21) second case: `½ J_g,bᵀ f_g,b`, the gravity part
/// as [`half_gradient_imu`] and the field part `½ J_bᵀ f_b`.
#[inline]
pub fn half_gradient_marg(q: Quat, a: Vec3, bx: f64, bz: f64, m: Vec3) -> Quat {
    quat(half_gradient_marg_of(q_of(q), v_of(a), bx, bz, v_of(m)))
}

#[inline(always)]
fn half_gradient_marg_of<T: Real>(q: Q<T>, a: V<T>, bx: T, bz: T, m: V<T>) -> Q<T> {
    let g = half_gradient_imu_of(q, a);
    let b = jt_f_of(&half_jacobian_b_of(q, bx, bz), &objective_b_of(q, bx, bz, m));
    core::array::from_fn(|i| g[i] + b[i])
}

/// (3) and (29) with the gyroscope alone: `q + ½ q ⊗ [0 ω] dt`, the product as
/// [`Quat::mul_pure`] and the ½ folded into dt (both products exact but for rounding
/// once: the same bits).
#[inline(always)]
fn predict_of<T: Real>(q: Q<T>, omega: V<T>, dt: T) -> Q<T> {
    let [w, x, y, z] = q;
    let [vx, vy, vz] = omega;
    let q_omega = [
        -(x * vx) - (y * vy + z * vz),
        w * vx + (y * vz - z * vy),
        (w * vy - x * vz) + z * vx,
        (w * vz + x * vy) - y * vx,
    ];
    let h = T::of(0.5) * dt;
    core::array::from_fn(|i| q[i] + q_omega[i] * h)
}

/// What [`correct_of`] found.
enum Corrected<T> {
    /// The new estimate, normalised, and whether the field was used.
    Next(Q<T>, bool),
    /// A squared norm outside the caller's fast range: the prediction, `½ ∇f`, `‖½ ∇f‖²`,
    /// `dt β` and whether the field was used, for the careful path
    /// ([`Madgwick::correct`]).
    Slow(Q<T>, Q<T>, T, T, bool),
    /// Lanes that differ on whether the field has a horizontal part.
    Mixed,
}

/// Eqs. (29)-(30) from the estimate `q`, the prediction `p` ([`predict_of`]) and the
/// normalised readings `â` and `m̂`, for one filter or for lanes: the field term (18)-(19)
/// when `m̂` has a horizontal part (`b_x > 0`), else (12)-(13); then `p − dt β ∇f/‖∇f‖`,
/// normalised. `inv_sqrt`: the caller's fast form, `None` outside its range.
#[inline(always)]
fn correct_of<T: Real>(
    q: Q<T>,
    p: Q<T>,
    a: V<T>,
    m: Option<V<T>>,
    dt: T,
    (beta_imu, beta_marg): (T, T),
    inv_sqrt: impl Fn(T) -> Option<T>,
) -> Corrected<T> {
    // A match, not a closure: LLVM left the closure out of line, and the call spilled
    // eight registers.
    let marg = match m {
        Some(m) => {
            let (bx, bz) = reference_field_of(q, m);
            match bx.decide(|v| v > 0.0) {
                Some(true) => Some(half_gradient_marg_of(q, a, bx, bz, m)),
                Some(false) => None,
                None => return Corrected::Mixed,
            }
        }
        None => None,
    };
    let used_mag = marg.is_some();
    let (gradient, beta) = match marg {
        Some(g) => (g, beta_marg),
        None => (half_gradient_imu_of(q, a), beta_imu),
    };
    let gg = dot_of(gradient, gradient);
    let k = beta * dt;
    if let Some(r) = inv_sqrt(gg) {
        let c = k * r;
        let next: Q<T> = core::array::from_fn(|i| p[i] - gradient[i] * c);
        if let Some(s) = inv_sqrt(dot_of(next, next)) {
            return Corrected::Next(next.map(|c| c * s), used_mag);
        }
    }
    Corrected::Slow(p, gradient, gg, k, used_mag)
}

/// The number of filters [`Madgwick::update_lanes`] steps at once.
pub(crate) const LANES: usize = Lane::LANES;

/// Madgwick's filter. Its state is the orientation alone, in its native North-West-Up frame.
#[derive(Clone, Debug, PartialEq)]
pub struct Madgwick {
    pub settings: MadgwickSettings,
    q: Quat,
    /// The rest-learned bias (zero unless `rest_bias_tau` is set).
    bias: Vec3,
    rest: RestBias,
}

impl Madgwick {
    pub fn new(settings: MadgwickSettings) -> Madgwick {
        let mut rest = RestBias::default();
        rest.prepare(settings.rest_bias_tau > 0.0);
        Madgwick { settings, q: Quat::IDENTITY, bias: Vec3::ZERO, rest }
    }

    /// The estimate `ᴱₛq̂_est` (sensor to earth, North-West-Up).
    pub fn quaternion(&self) -> Quat {
        self.q
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

    /// The gyroscope bias being subtracted (learned at rest when `rest_bias_tau` is set).
    pub fn bias(&self) -> Vec3 {
        self.bias
    }

    /// True when the last sample counted as rest (only tracked with `rest_bias_tau` set).
    pub fn at_rest(&self) -> bool {
        self.rest.at_rest()
    }

    /// Sets the estimate; `q` must be a unit quaternion.
    pub fn set_quaternion(&mut self, q: Quat) {
        self.q = q;
    }

    /// After a gap: the re-acquired estimate, rest detection started over, bias kept; for
    /// the rest watch's re-acquisition of a still sensor, a bias the rest-bias learner
    /// learns, or one it learned before it was switched off (still subtracted), is the
    /// gyroscope's reading.
    pub(crate) fn reacquire(&mut self, r: &crate::filters::pipeline::estimator::Reacquisition) -> bool {
        let (q, used_mag) = r.plain();
        self.q = q;
        if let Some(g) = r.still.filter(|_| self.settings.rest_bias_tau > 0.0 || self.bias != Vec3::ZERO) {
            self.bias = g;
        }
        self.rest.restart();
        used_mag
    }

    /// [`LANES`] filters' steps at once, each with an accelerometer reading and all with or all
    /// without a magnetometer reading; bit-identical to calling [`Madgwick::update`] on
    /// each, since both are [`predict_of`] and [`correct_of`]. The samples are those the
    /// usual step takes (`Runner::lane_usual`). `None`, with nothing changed, when a lane
    /// meets an edge case (a squared norm outside [`inv_sqrt`]'s fast range, or lanes that
    /// differ on whether the field has a horizontal part). Inlined into the group's loop:
    /// called, it took the checked samples through a copy on the stack
    /// (docs/PERFORMANCE.md).
    #[inline(always)]
    pub(crate) fn update_lanes(fs: &mut [&mut Madgwick; LANES], u: &[Usual; LANES]) -> Option<Step> {
        // Runner::lane_usual takes no filter with a kind option (the rest-bias learner);
        // Filter::try_lanes pairs samples with an accelerometer reading each and the same
        // magnetometer presence.
        debug_assert!(fs.iter().all(|f| f.usual_settings()));
        debug_assert!(u.iter().all(|v| v.accel.is_some() && v.mag.is_some() == u[0].mag.is_some()));
        let lane = |g: &dyn Fn(usize) -> f64| Lane::new(core::array::from_fn(g));
        let vector = |v: &dyn Fn(usize) -> Vec3| [lane(&|i| v(i).x), lane(&|i| v(i).y), lane(&|i| v(i).z)];
        // A reading's direction as `Checked::unit` gives it: v √n² (1/n²), its squared
        // norm n² taken by the quick check (in inv_sqrt's fast range).
        let unit = |c: &dyn Fn(usize) -> Option<Checked>| {
            let n2 = lane(&|i| c(i).map_or(1.0, Checked::norm_squared));
            let r = crate::math::inv_sqrt_in_range(n2);
            vector(&|i| c(i).map_or(Vec3::ZERO, |c| c.v)).map(|x| x * r)
        };
        let q = [lane(&|i| fs[i].q.w), lane(&|i| fs[i].q.x), lane(&|i| fs[i].q.y), lane(&|i| fs[i].q.z)];
        let omega = vector(&|i| u[i].gyro - fs[i].bias);
        let dt = lane(&|i| u[i].dt);
        // The same source as the one-filter step (`Madgwick::step`), in lanes.
        let p = predict_of(q, omega, dt);
        let a = unit(&|i| u[i].accel);
        let m = u[0].mag.is_some().then(|| unit(&|i| u[i].mag));
        let betas = (lane(&|i| fs[i].settings.beta_imu), lane(&|i| fs[i].settings.beta_marg));
        let Corrected::Next(out, used_mag) =
            correct_of(q, p, a, m, dt, betas, crate::math::inv_sqrt_fast_lanes)
        else {
            return None;
        };
        let out = out.map(Lane::to_array);
        for (i, f) in fs.iter_mut().enumerate() {
            f.q = Quat::new(out[0][i], out[1][i], out[2][i], out[3][i]);
        }
        Some(Step { used_accel: true, used_mag, initializing: false })
    }

    /// One filter step, eqs. (29)-(30). `gyro` in rad/s, `accel` and `mag` in any unit
    /// (they are normalised) and not zero, `dt` in seconds and positive.
    ///
    /// The state changes only when the new estimate is finite; otherwise it stays as it
    /// was and `None` is returned.
    #[inline(always)]
    pub fn update(&mut self, dt: f64, gyro: Vec3, accel: Option<Vec3>, mag: Option<Vec3>) -> Option<Step> {
        if self.settings.rest_bias_tau > 0.0 {
            return self.update_with_rest_bias(dt, gyro, accel, mag);
        }
        let (q, step) =
            self.step::<false>(self.bias, dt, gyro, accel.map(Vec3::normalized), mag.map(Vec3::normalized))?;
        self.q = q;
        Some(step)
    }

    /// The rest-bias option off: the settings [`Madgwick::update_usual`] is for.
    pub(crate) fn usual_settings(&self) -> bool {
        self.settings.rest_bias_tau == 0.0
    }

    /// [`Madgwick::update`]'s usual case, which calls no function, for the
    /// [`Madgwick::usual_settings`]: every squared norm in [`inv_sqrt`]'s fast range. The
    /// same result, or `None` with nothing changed otherwise.
    #[inline(always)]
    pub(crate) fn update_usual(&mut self, s: &Usual) -> Option<u32> {
        debug_assert!(self.usual_settings());
        // One copy of the step per case, so that each knows which readings it has (and
        // the flags it leaves are constants, computed before the copies join).
        let (bias, dt, gyro) = (self.bias, s.dt, s.gyro);
        let flags = |had_accel, had_mag| move |(q, step): (Quat, Step)| (q, step.flags(had_accel, had_mag));
        let (q, flags) = match (s.accel, s.mag) {
            (Some(a), None) => {
                self.step::<true>(bias, dt, gyro, Some(a.unit()), None).map(flags(true, false))
            }
            (Some(a), Some(m)) => {
                let (a, m) = Checked::heading_units(a, m)?;
                self.step::<true>(bias, dt, gyro, Some(a), Some(m)).map(flags(true, true))
            }
            (None, m) => {
                self.step::<true>(bias, dt, gyro, None, m.map(Checked::unit)).map(flags(false, m.is_some()))
            }
        }?;
        self.q = q;
        Some(flags)
    }

    /// [`Madgwick::update`] with the rest-bias option: the detector's state and the bias
    /// change only when the step succeeds. Kept apart so the plain update copies no
    /// detector.
    #[inline(never)]
    fn update_with_rest_bias(
        &mut self,
        dt: f64,
        gyro: Vec3,
        accel: Option<Vec3>,
        mag: Option<Vec3>,
    ) -> Option<Step> {
        let (detector, bias) = self.rest.update(dt, gyro, accel, self.settings.rest_bias_tau, self.bias);
        let (q, step) =
            self.step::<false>(bias, dt, gyro, accel.map(Vec3::normalized), mag.map(Vec3::normalized))?;
        self.q = q;
        self.bias = bias;
        self.rest.commit(detector);
        Some(step)
    }

    /// Eqs. (29)-(30) from the current estimate with gyro bias `bias` and the normalised
    /// readings `â` and `m̂`: the new estimate, or `None` when it is not finite. `USUAL`:
    /// only the usual case, which calls no function (every squared norm in [`inv_sqrt`]'s
    /// fast range), `None` otherwise.
    #[inline(always)]
    fn step<const USUAL: bool>(
        &self,
        bias: Vec3,
        dt: f64,
        gyro: Vec3,
        a: Option<Vec3>,
        m: Option<Vec3>,
    ) -> Option<(Quat, Step)> {
        let q = q_of(self.q);
        let p = predict_of(q, v_of(gyro - bias), dt);
        let mut step = Step::default();
        let Some(a) = a else {
            let p = quat(p);
            let p = if USUAL { p.try_normalized_usual() } else { p.try_normalized() };
            return Some((p?, step));
        };
        step.used_accel = true;
        // The usual case: ‖∇f‖² and the result's squared norm in inv_sqrt's fast range.
        // Then every value is finite (a squared norm under 1e300 bounds each component,
        // and the scale is at most 1e150), so the result needs no test; anything else
        // takes `correct`, the same operations with every test.
        //
        // In the usual case the upper bounds need no test: with a unit q and unit
        // readings each component of ∇f is a sum of a few products of components below 1
        // (and of b_x, b_z ≤ 1), so ‖∇f‖² < 1e3; and ‖next‖ ≤ ‖p‖ + dt β ≤
        // 1 + ½ dt |ω| + dt β < 1e12 for dt ≤ 1e6 s, |ω − b| < 2e5 rad/s and β ≤ 100.
        let fast = |x: f64| if USUAL { inv_sqrt_fast_bounded(x) } else { inv_sqrt_fast(x) };
        let betas = (self.settings.beta_imu, self.settings.beta_marg);
        match correct_of(q, p, v_of(a), m.map(v_of), dt, betas, fast) {
            Corrected::Next(next, used_mag) => {
                step.used_mag = used_mag;
                Some((quat(next), step))
            }
            Corrected::Slow(p, gradient, gg, k, used_mag) if !USUAL => {
                step.used_mag = used_mag;
                Some((Self::correct(quat(p), quat(gradient), gg, k)?, step))
            }
            // One filter's lanes cannot differ.
            Corrected::Slow(..) | Corrected::Mixed => None,
        }
    }

    /// (29)-(30), the correction of the prediction `p` by the gradient `∇f` (with
    /// `gg = ‖∇f‖²`, `k = dt β`): the new estimate normalised, or `None` when it is not
    /// finite. [`Madgwick::step`] has its usual case inline, and this after it: out of
    /// line, its quaternion arguments were stored to the stack on every update.
    #[inline(always)]
    fn correct(p: Quat, gradient: Quat, gg: f64, k: f64) -> Option<Quat> {
        if gg.is_nan() || gg <= 0.0 {
            // A zero gradient has no direction: the prediction stands.
            return p.try_normalized();
        }
        (p - gradient.scale(k * inv_sqrt(gg))).try_normalized()
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

    estimator!(impl for Madgwick { settings: MadgwickSettings, native: Nwu, own_startup: false, diagnostics: GYRO_BIAS | REST, usual: true } {
        fn configure(&mut self, settings: MadgwickSettings) {
            self.settings = settings;
            // Without the rest learner, b is no estimate any more: dropped, or a bias learned
            // before would be subtracted for good.
            if settings.rest_bias_tau == 0.0 {
                self.bias = Vec3::ZERO;
            }
            self.rest.prepare(settings.rest_bias_tau > 0.0);
        }

        fn restart(&mut self, settings: MadgwickSettings) {
            // As new(settings), keeping the detector's box: no allocation.
            self.settings = settings;
            self.q = Quat::IDENTITY;
            self.bias = Vec3::ZERO;
            self.rest.restart();
            self.rest.prepare(settings.rest_bias_tau > 0.0);
        }

        #[inline(always)]
        fn update(&mut self, dt: f64, gyro: Vec3, accel: Option<Vec3>, mag: Option<Vec3>) -> Option<Step> {
            Madgwick::update(self, dt, gyro, accel, mag)
        }

        fn fields(&self) -> u32 {
            // Madgwick's filter estimates no bias; with the rest-bias option it has one.
            if self.settings.rest_bias_tau > 0.0 {
                diag::GYRO_BIAS | diag::REST
            } else {
                0
            }
        }

        fn diagnose(&self, d: &mut Diagnostics) {
            d.gyro_bias = self.bias();
            d.rest = if Madgwick::at_rest(self) { 1.0 } else { 0.0 };
        }

        fn at_rest(&self) -> bool {
            self.settings.rest_bias_tau > 0.0 && Madgwick::at_rest(self)
        }
    });
}
