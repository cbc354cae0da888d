//! GMVDK: gyroscope prediction, accelerometer and magnetometer corrections each scaled
//! by SLERP with trust α and μ_K, fused by a second SLERP.
//!
//! Source: "GMVDK" double-SLERP MARG orientation estimator, Micromachines 15:553, 2024
//! (`shared/papers/gmvdk-2024-double-slerp.txt`): Figure 1, eqs. (7)-(24), Appendix B.
//! Equation numbers are the paper's.
//!
//! Per sample, after start-up:
//! 1. `ω_B = ω − b` (de-biased gyroscope), `q̇ = ½ q_out ⊗ ω_B` (7), `q_G = q_out + q̇ dt`,
//!    normalised (8);
//! 2. accelerometer pipeline: `a(q_G) = q_G* ⊗ A_init ⊗ q_G` (9); `Δq_A` the rotation from
//!    `a0` to `a(q_G)`, built as `H(a0 × a(q_G), |a0||a(q_G)| + a0·a(q_G))` (10)-(12);
//!    `q_GA = q_G ⊗ Δq_A` (13); `q_SA = SLERP(q_G, q_GA, α)` (14)-(16);
//! 3. magnetometer pipeline, the same with `M_init`, `m0` and μ_K: `q_SM`;
//! 4. `q_out = SLERP(q_SM, q_SA, ½)` (17).
//!
//! Trust parameters (Appendix B):
//! - `α = max(0, Stillness·SlopeAlpha + 1 − SlopeAlpha)` (B.1), SlopeAlpha = 1.0. The
//!   paper reads Stillness from its sensor module and says a normalised average of the
//!   mean squared gyroscope and accelerometer readings works as well. Here:
//!   `activity = ½ (E[|ω_B|²]/σ_ω² + E[(|a| − g0)²]/σ_a²)`, the expectations being
//!   exponential moving averages with time constant `activity_tau`, and
//!   `Stillness = max(0, 1 − activity)`: 1 when still, 0 once the mean squared activity
//!   reaches its scale (σ_ω = `gyro_activity`, σ_a = `accel_activity`).
//! - μ_K (B.2), SlopeMuk = 1.5: `m0i = q_out ⊗ m0 ⊗ q_out*` with the previous output;
//!   λ the angle between `m0i` and `M_init`; `μ_KA = 1 − SlopeMuk·λ`,
//!   `μ_KM = 1 − (|m0i|/|M_init|)·λ`, each floored at 0; `μ_1 = (μ_KA + μ_KM)/2`;
//!   `μ_2 = min μ_1 over the last 0.4 s` (a window in time, kept as a monotonic queue:
//!   amortised O(1), fixed memory, exact to 1/1000 of the window); `μ_K = μ_2·α` (24).
//!
//! Start-up and bias: `A_init`, `M_init` and the first bias are the means over a static
//! period of `init_duration` s. Afterwards, whenever α ≥ `static_alpha`, gyroscope
//! samples are collected; once a static run reaches `bias_window` s, a least-squares
//! line through each axis gives the new bias (its value at the run's end), as the
//! paper's "linear regression on a window of consecutive samples". A run broken by
//! motion is discarded.
//!
//! Choices:
//! - Frames: the paper's frames are left-handed with (x, y, z, w) quaternions and its
//!   inertial frame is the start-up body frame. orient runs the same equations with
//!   Hamilton quaternions in a right-handed East-North-Up frame, with `A_init` and
//!   `M_init` rotated into it by the start-up attitude (from the mean accelerometer and
//!   magnetometer). Every step is equivariant under that constant rotation, so the
//!   trajectory is the paper's, expressed in the earth frame; `relative_output` reports
//!   it relative to the start-up pose as the paper does.
//! - (17)'s interpolation parameter is printed as "%" in the extracted text, the usual
//!   rendering of "½": the two scaled estimates are fused with equal weight.
//! - (8) is read as first-order integration followed by normalisation.
//! - Without a magnetometer reading the magnetometer pipeline contributes `q_SM = q_G`,
//!   as it does when μ_K = 0.

use super::params::{settings, Switch};
use super::startup::{stationary_norm, StartupMeans, Stillness, GRAVITY_STILL};
use super::Step;
use crate::math::{asin_over, cos_and_sinc, inv_sqrt, inv_sqrt_fast, Frame, Quat, Vec3};

settings! {
    /// GMVDK's settings.
    pub struct GmvdkSettings {
        slope_alpha: f64 = GMVDK_SLOPE_ALPHA 56 {
            unit: "1",
            default: 1.0,
            min: 0.0,
            max: 100.0,
            zero_off: false,
            doc: "SlopeAlpha of Appendix B.1: alpha = max(0, stillness*slope + 1 - slope); default \
                 1.0 (paper).",
        },
        slope_muk: f64 = GMVDK_SLOPE_MUK 57 {
            unit: "1/rad",
            default: 1.5,
            min: 0.0,
            max: 100.0,
            zero_off: false,
            doc: "SlopeMuk of Appendix B.2 / eq. (20): muKA = 1 - slope*lambda; default 1.5 (paper).",
        },
        mu_window: f64 = GMVDK_MU_WINDOW 58 {
            unit: "s",
            default: 0.4,
            min: 0.0,
            max: 60.0,
            zero_off: false,
            doc: "Window of the running minimum mu2 of mu1 (section 2.2.2); default 0.4 (paper).",
        },
        init_duration: f64 = GMVDK_INIT_DURATION 59 {
            unit: "s",
            default: 1.0,
            min: 0.0,
            max: 3600.0,
            zero_off: false,
            doc: "Static start-up period averaging A_init, M_init and the first gyro bias; default 1 \
                 (orient: the paper averages a static start-up period without giving its length).",
        },
        activity_tau: f64 = GMVDK_ACTIVITY_TAU 60 {
            unit: "s",
            default: 0.1,
            min: 1e-4,
            max: 100.0,
            zero_off: false,
            doc: "Time constant of the mean-square activity averages behind stillness; default 0.1 \
                 (orient: the paper reads Stillness from its sensor module; with 0.1 s, alpha falls \
                 within a tenth of a second of the start of motion).",
        },
        gyro_activity: f64 = GMVDK_GYRO_ACTIVITY 61 {
            unit: "rad/s",
            default: 0.5,
            min: 1e-6,
            max: 100.0,
            zero_off: false,
            doc: "Gyro activity scale: RMS de-biased rate at which stillness reaches 0 (with no \
                 accelerometer activity, at sqrt(2) times it); default 0.5 (orient: about 30 deg/s, \
                 slow deliberate motion).",
        },
        accel_activity: f64 = GMVDK_ACCEL_ACTIVITY 62 {
            unit: "m/s^2",
            default: 1.0,
            min: 1e-6,
            max: 1000.0,
            zero_off: false,
            doc: "Accelerometer activity scale: RMS deviation of |a| from its start-up value at \
                 which stillness reaches 0 (alone: sqrt(2) times it); default 1.0 (orient: about 0.1 g \
                 of linear acceleration).",
        },
        bias_window: f64 = GMVDK_BIAS_WINDOW 63 {
            unit: "s",
            default: 1.0,
            min: 1e-3,
            max: 3600.0,
            zero_off: false,
            doc: "Static run length for the linear-regression gyro de-biasing of the paper's step 1; \
                 default 1.0 (orient: the paper's 'window of consecutive samples' has no length).",
        },
        static_alpha: f64 = GMVDK_STATIC_ALPHA 64 {
            unit: "1",
            default: 0.95,
            min: 0.0,
            max: 1.0,
            zero_off: false,
            doc: "alpha at or above which the sensor counts as static for de-biasing; default 0.95 \
                 (orient: the paper says 'estimated to be static' without a threshold).",
        },
        relative_output: Switch = GMVDK_RELATIVE_OUTPUT 65 {
            unit: "1",
            default: 0.0,
            min: 0.0,
            max: 1.0,
            zero_off: false,
            doc: "1: report orientation relative to the start-up pose (the paper's output); 0 \
                 (default): in the configured earth frame.",
        },
    }
    shared { gravity: f64 = GRAVITY }
}

/// `SLERP(q1, q2, h)`, eqs. (15)-(16), along the shorter arc; linear interpolation
/// (normalised) when the two are within 1e-6 rad.
///
/// The weights are `sin((1 − h)ω)/sin ω` and `sin(hω)/sin ω` with `cos ω = q1·q2`. For
/// `sin ω < 1/20` and `(hω)² < 1/256` (the usual filter step, whose corrections are
/// small, with `h` in [0, 1]) they come from
/// series in `sin²ω = (1 − cos ω)(1 + cos ω)` alone: `ω = sin ω · asin(s)/s`
/// ([`asin_over`]), `sin(hω)/sin ω = h · asin(s)/s · sin(hω)/(hω)` and `cos(hω)`
/// ([`cos_and_sinc`]), with no arccosine, sine, root or division. Larger angles take
/// `slerp_weights_by_acos`, the readable form, which a test compares the series with.
#[inline(always)]
pub fn slerp(q1: Quat, q2: Quat, h: f64) -> Quat {
    let mut cos = q1.dot(q2);
    let mut q2 = q2;
    if cos < 0.0 {
        cos = -cos;
        q2 = q2.scale(-1.0);
    }
    if cos > 1.0 - 1e-12 {
        return (q1.scale(1.0 - h) + q2.scale(h)).normalized();
    }
    let (w1, w2) = slerp_weights(cos, h);
    (q1.scale(w1) + q2.scale(w2)).normalized()
}

/// (10)-(12): `Δq = H(q₀, Δ)` with `Δ = v₀ × v̂` (11) and `q₀ = |v₀||v̂| + v₀·v̂` (12),
/// normalised: the rotation that takes the reading `v₀` onto the prediction `v̂`
/// ((9)'s `a(q_G)`, or the magnetometer's), so that `q_G ⊗ Δq` maps the initial vector
/// onto the reading (13). The same rotation as [`Quat::from_two_vectors`]`(v₀, v̂)`,
/// which normalises both vectors first: two divisions more (a test compares them).
///
/// `|Δq|² = q₀² + |Δ|² = 2 |v₀||v̂| q₀`: the normalisation takes that product, not Δq's
/// four squares. Its relative error is q₀'s, about 2⁻⁵³ |v₀||v̂| / q₀, plus up to twice
/// that of the norms passed (the update passes the reference's stored norm, a few ulp
/// from the rotated prediction's). It is used while `q₀ > |v₀||v̂| / 2` (the reading
/// within 120° of the prediction), where that is a few ulp; the SLERPs that take Δq
/// normalise their results. Readings farther off (the last of them pointing opposite,
/// with no unique axis), or so small or large that `|Δq|²` leaves `inv_sqrt`'s fast
/// range, go to `from_two_vectors`, out of line. Taking the product costs GMVDK's MARG
/// update fewer instructions than normalising by the four squares (docs/PERFORMANCE.md).
#[inline(always)]
pub fn eq10_to_12(v0: Vec3, v: Vec3) -> Quat {
    eq10_to_12_with_norms(v0, v0.norm(), v, v.norm())
}

/// [`eq10_to_12`] with the norms given: the update has the reading's already (α's
/// accelerometer term, or for the magnetometer the `|m0|` that (19)-(22) use), and the
/// prediction `v̂ = q_G* ⊗ v_ref ⊗ q_G` (9) has the norm of
/// its reference `v_ref`, which [`Reference`] keeps; the update passes those instead of
/// two more square roots each step (equal to rounding; a test compares).
#[inline(always)]
fn eq10_to_12_with_norms(v0: Vec3, v0_norm: f64, v: Vec3, v_norm: f64) -> Quat {
    let nn = v0_norm * v_norm;
    let q0 = nn + v0.dot(v);
    if q0 > 0.5 * nn {
        if let Some(r) = inv_sqrt_fast(2.0 * nn * q0) {
            let d = v0.cross(v);
            return Quat::new(q0, d.x, d.y, d.z).scale(r);
        }
    }
    from_two_vectors_outline(v0, v)
}

#[cold]
#[inline(never)]
fn from_two_vectors_outline(v0: Vec3, v: Vec3) -> Quat {
    Quat::from_two_vectors(v0, v)
}

/// `SLERP(1, r, h)`: [`slerp`] from the identity, whose dot product with `r` is `r.w`
/// and whose terms are the weight alone. SLERP is left-invariant
/// (`SLERP(q ⊗ a, q ⊗ b, h) = q ⊗ SLERP(a, b, h)` for a unit `q`, since
/// `(q ⊗ a)·(q ⊗ b) = a·b`), so `SLERP(q_g, q_g ⊗ Δq, h) = q_g ⊗ SLERP(1, Δq, h)`; a test compares the
/// two sides. At exactly half a turn (`r.w = 0`) both arcs are shortest: this form
/// takes `r`'s, the paper's form whichever the rounding of `q_g·(q_g ⊗ Δq)` picks.
/// For a unit `r` and `h` in [0, 1] the result is unit before its normalisation, to
/// rounding, so that needs no range test.
#[inline(always)]
pub fn slerp_from_identity(r: Quat, h: f64) -> Quat {
    slerp_from_identity_terms(r, h).0.normalized_in_range()
}

/// [`slerp_from_identity`] before its normalisation, and whether that is the linear
/// interpolation of nearly equal ends (whose norm falls short of 1 by up to 2.5e-13),
/// not the weights' result (unit to rounding).
#[inline(always)]
fn slerp_from_identity_terms(r: Quat, h: f64) -> (Quat, bool) {
    let r = if r.w < 0.0 { r.scale(-1.0) } else { r };
    let cos = r.w;
    if cos > 1.0 - 1e-12 {
        return (Quat::new((1.0 - h) + h * r.w, h * r.x, h * r.y, h * r.z), true);
    }
    let (w1, w2) = slerp_weights(cos, h);
    (Quat::new(w1 + w2 * r.w, w2 * r.x, w2 * r.y, w2 * r.z), false)
}

/// An end of (17)'s `SLERP(q_sm, q_sa, ½)`: [`slerp_from_identity`], normalised only where
/// it is not unit to rounding. [`slerp_half`] normalises the sum of its ends, so ends a
/// few ulps off unit move the result by rounding only: two normalisations fewer per step.
#[inline(always)]
fn slerp_from_identity_for_half(r: Quat, h: f64) -> Quat {
    match slerp_from_identity_terms(r, h) {
        (q, true) => q.normalized_in_range(),
        (q, false) => q,
    }
}

/// [`slerp`]'s weights `(sin((1 − h)ω)/sin ω, sin(hω)/sin ω)` for `cos ω` in
/// `[0, 1 − 1e-12]`: the series, or [`slerp_weights_by_acos`].
#[inline(always)]
fn slerp_weights(cos: f64, h: f64) -> (f64, f64) {
    let s2 = (1.0 - cos) * (1.0 + cos);
    if s2 < 1.0 / 400.0 {
        let a = asin_over(s2); // ω / sin ω
        let x2 = h * h * (s2 * (a * a)); // (hω)²: under 1/256 for h in [0, 1]
        if x2 < 1.0 / 256.0 {
            let (c_h, sinc_h) = cos_and_sinc(x2);
            let w2 = h * a * sinc_h;
            return (c_h - cos * w2, w2);
        }
    }
    slerp_weights_by_acos(cos, h)
}

/// [`slerp`]'s weights from `ω = acos(q1·q2)` and one `sincos`, for `q2` on the shorter
/// arc and `cos = q1·q2` under `1 − 1e-12`.
#[cold]
#[inline(never)]
fn slerp_weights_by_acos(cos: f64, h: f64) -> (f64, f64) {
    let omega = libm::acos(cos);
    // sin ω from cos ω (ω in [0, π/2] after the flip): one square root instead of a
    // sine, and accurate near ω = 0 where it is formed as (1 − cos)(1 + cos).
    let r = inv_sqrt((1.0 - cos) * (1.0 + cos));
    // sin((1 − h)ω) = sin ω cos(hω) − cos ω sin(hω): both weights from one sincos. The
    // first, cos(hω) − cos ω sin(hω)/sin ω, is near 1 − h and loses nothing to
    // cancellation but absolutely, where its q1 term is that small anyway.
    let (s_h, c_h) = libm::sincos(h * omega);
    let w2 = s_h * r;
    (c_h - cos * w2, w2)
}

/// [`slerp`] by [`slerp_weights_by_acos`] whatever the angle: the readable form the
/// series is tested against.
#[cfg(test)]
fn slerp_by_acos(q1: Quat, q2: Quat, cos: f64, h: f64) -> Quat {
    let (w1, w2) = slerp_weights_by_acos(cos, h);
    (q1.scale(w1) + q2.scale(w2)).normalized()
}

/// `SLERP(q1, q2, ½)`: the normalised sum along the shorter arc. Equal to [`slerp`] with
/// `h = ½`, whose two weights are then both `sin(ω/2)/sin ω`, without its arccosine and
/// sines. For unit `q1` and `q2`, `|q1 + q2|² = 2 + 2 q1·q2` is at least 2 on the shorter
/// arc, so the normalisation needs no range test.
pub fn slerp_half(q1: Quat, q2: Quat) -> Quat {
    let q2 = if q1.dot(q2) < 0.0 { q2.scale(-1.0) } else { q2 };
    (q1 + q2).normalized_in_range()
}

/// (19): `λ = acos(cos λ)`. For the small angles of an undisturbed field
/// (`s² = (1 − cos λ)/2` under 1/256: λ under 7.2°) as `2 asin(s)`, `s = sin(λ/2)`, by
/// [`asin_over`]'s series (`1 − cos λ` is exact there): a square root and the series
/// instead of libm's `acos`. Larger angles take `acos`, out of line; a test compares the
/// two forms.
#[inline(always)]
fn eq19_lambda(cos_l: f64) -> f64 {
    let s2 = 0.5 * (1.0 - cos_l);
    if s2 < 1.0 / 256.0 {
        return 2.0 * s2.sqrt() * asin_over(s2);
    }
    acos_outline(cos_l)
}

#[cold]
#[inline(never)]
fn acos_outline(c: f64) -> f64 {
    libm::acos(c)
}

/// M_init from the first magnetometer reading `m0` after start-up was skipped (a known
/// attitude) or had none: `m0` in the earth frame, through the attitude `q` tilted by the
/// least rotation that takes the accelerometer reading `a0` of the same sample onto its
/// reference `a_ref`. The paper takes A_init and M_init at one still instant, so that the
/// field's dip against gravity is the one measured; through `q` alone, an attitude whose
/// inclination is off (the identity on a tilted sensor) would give M_init another dip,
/// which no attitude reconciles with A_init, and the double SLERP would settle between
/// the two corrections, off in inclination for good.
#[cold]
#[inline(never)]
fn first_field(q: Quat, a0: Vec3, a_ref: Vec3, m0: Vec3) -> Reference {
    let tilt = Quat::from_two_vectors(q.rotate(a0), a_ref);
    Reference::new(tilt.rotate(q.rotate(m0)))
}

/// A reference vector of (9) (the initial accelerometer or magnetometer reading in the
/// earth frame; after `set_quaternion`, the next accelerometer reading's norm along up)
/// and its norm, computed once where the reference is set: the update's
/// predictions `q_G* ⊗ v ⊗ q_G` keep that norm (a rotation does), and (12) and (19)-(22)
/// read it. Snapshots hold the vector only; the norm is derived again on load.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Reference {
    v: Vec3,
    norm: f64,
}

impl Reference {
    fn new(v: Vec3) -> Reference {
        Reference { v, norm: v.norm() }
    }

    /// Visits the vector of an optional reference (`c.opt_vec3`) and derives the norm
    /// of what comes back: the same on save, the loaded vector's on load.
    fn codec(r: &mut Option<Reference>, c: &mut dyn super::state::Codec) {
        let mut v = r.map(|r| r.v);
        c.opt_vec3(&mut v);
        *r = v.map(Reference::new);
    }
}

const WINDOW_SLOTS: usize = 1024;

/// Running minimum over a time window: a monotonic queue in a fixed ring buffer.
/// Entries closer than window/1000 in time share a slot, so the buffer never overflows
/// and the window is exact to that resolution.
#[derive(Clone, Debug, PartialEq)]
struct MinWindow {
    t: [f64; WINDOW_SLOTS],
    v: [f64; WINDOW_SLOTS],
    head: usize,
    len: usize,
}

impl MinWindow {
    fn new() -> MinWindow {
        MinWindow { t: [0.0; WINDOW_SLOTS], v: [0.0; WINDOW_SLOTS], head: 0, len: 0 }
    }

    fn back(&self) -> usize {
        (self.head + self.len - 1) % WINDOW_SLOTS
    }

    /// The minimum over `(now − window, now]` if `value` were added at `now`, without
    /// adding it.
    fn peek(&self, now: f64, value: f64, window: f64) -> f64 {
        (0..self.len)
            .map(|k| (self.head + k) % WINDOW_SLOTS)
            .find(|&i| self.t[i] > now - window)
            .map_or(value, |i| self.v[i].min(value))
    }

    /// Adds `value` at time `now` and returns the minimum over `(now − window, now]`.
    fn push(&mut self, now: f64, value: f64, window: f64) -> f64 {
        while self.len > 0 && self.t[self.head] <= now - window {
            self.head = (self.head + 1) % WINDOW_SLOTS;
            self.len -= 1;
        }
        while self.len > 0 && self.v[self.back()] >= value {
            self.len -= 1;
        }
        let resolution = window / 1000.0;
        let merge = self.len > 0 && now - self.t[self.back()] < resolution;
        if !merge {
            if self.len == WINDOW_SLOTS {
                // Unreachable with the resolution above; keep the newest if it happens.
                self.head = (self.head + 1) % WINDOW_SLOTS;
                self.len -= 1;
            }
            let i = (self.head + self.len) % WINDOW_SLOTS;
            self.t[i] = now;
            self.v[i] = value;
            self.len += 1;
        }
        self.v[self.head]
    }
}

/// Least-squares line through (t, ω) per axis, by running sums.
#[derive(Clone, Debug, Default, PartialEq)]
struct Regression {
    n: f64,
    t0: f64,
    st: f64,
    stt: f64,
    sy: Vec3,
    sty: Vec3,
    last_t: f64,
}

impl Regression {
    fn add(&mut self, t: f64, y: Vec3) {
        if self.n == 0.0 {
            self.t0 = t;
        }
        let t = t - self.t0;
        self.n += 1.0;
        self.st += t;
        self.stt += t * t;
        self.sy = self.sy + y;
        self.sty = self.sty + y * t;
        self.last_t = t;
    }

    fn duration(&self) -> f64 {
        if self.n == 0.0 {
            0.0
        } else {
            self.last_t
        }
    }

    /// The fitted value at the last sample time.
    fn value_at_end(&self) -> Vec3 {
        let d = self.n * self.stt - self.st * self.st;
        if self.n < 2.0 || d.abs() < 1e-300 {
            return self.sy * (1.0 / self.n);
        }
        let slope = (self.sty * self.n - self.sy * self.st) * (1.0 / d);
        let intercept = (self.sy - slope * self.st) * (1.0 / self.n);
        intercept + slope * self.last_t
    }
}

/// The trust values of the last update.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Trust {
    pub alpha: f64,
    pub mu_ka: f64,
    pub mu_km: f64,
    pub mu_k: f64,
}

/// GMVDK. Native frame: East-North-Up.
#[derive(Clone, Debug, PartialEq)]
pub struct Gmvdk {
    pub settings: GmvdkSettings,
    q: Quat,
    q_start: Quat,
    bias: Vec3,
    a_init: Option<Reference>,
    m_init: Option<Reference>,
    g0: f64,
    ms_gyro: f64,
    ms_accel: f64,
    time: f64,
    startup: Option<StartupMeans>,
    regression: Regression,
    /// Boxed at creation (16 KiB): keeps the other kinds' handles small; never
    /// reallocated by an update.
    window: Box<MinWindow>,
    trust: Trust,
    mag_seen: bool,
}

impl Gmvdk {
    pub fn new(settings: GmvdkSettings) -> Gmvdk {
        crate::isa::prepare();
        Gmvdk {
            settings,
            q: Quat::IDENTITY,
            q_start: Quat::IDENTITY,
            bias: Vec3::ZERO,
            a_init: None,
            m_init: None,
            g0: 0.0,
            ms_gyro: 0.0,
            ms_accel: 0.0,
            time: 0.0,
            startup: Some(StartupMeans::default()),
            regression: Regression::default(),
            window: Box::new(MinWindow::new()),
            trust: Trust::default(),
            mag_seen: false,
        }
    }

    /// Back to the state of [`Gmvdk::new`] with the current settings, keeping the
    /// window's allocation: no heap use after creation.
    pub fn reset(&mut self) {
        self.window.head = 0;
        self.window.len = 0;
        self.q = Quat::IDENTITY;
        self.q_start = Quat::IDENTITY;
        self.bias = Vec3::ZERO;
        self.a_init = None;
        self.m_init = None;
        self.g0 = 0.0;
        self.ms_gyro = 0.0;
        self.ms_accel = 0.0;
        self.time = 0.0;
        self.startup = Some(StartupMeans::default());
        self.regression = Regression::default();
        self.trust = Trust::default();
        self.mag_seen = false;
    }

    /// The output: ENU, or relative to the start-up pose with `relative_output`.
    pub fn quaternion(&self) -> Quat {
        if self.settings.relative_output.on() {
            self.q_start.conj() * self.q
        } else {
            self.q
        }
    }

    /// The start-up pose (ENU) that a relative output is relative to.
    pub fn start_pose(&self) -> Quat {
        self.q_start
    }

    /// The orientation in ENU, whatever `relative_output` says.
    pub fn absolute_quaternion(&self) -> Quat {
        self.q
    }

    /// After a gap: the re-acquired attitude (the start-up pose that a relative output
    /// refers to is kept), the static-run regression started over, the bias kept. The
    /// gap counts as time, so the μ window forgets the readings before it.
    pub(crate) fn reacquire(&mut self, r: &super::Reacquisition) -> bool {
        let (q, used_mag) = r.plain();
        self.q = q;
        self.time += r.dt;
        self.regression = Regression::default();
        self.mag_seen = false;
        used_mag
    }

    /// Takes new settings, the state kept but for the stationary norm g0: one that is not
    /// the new configured gravity's within `GRAVITY_STILL` (a start-up must read it so
    /// too) becomes that gravity, or the stillness behind α would stay at zero, and the
    /// accelerometer distrusted, for good.
    pub(crate) fn configure(&mut self, settings: GmvdkSettings) {
        self.settings = settings;
        self.g0 = stationary_norm(self.g0, settings.gravity);
    }

    /// A known initial attitude (ENU): start-up is skipped; A_init is the configured
    /// gravity along up, and M_init the first field that comes with an accelerometer
    /// reading of gravity's norm (within `GRAVITY_STILL`), rotated into the earth frame
    /// with the dip it makes with that reading (see `first_field`): one glitched reading
    /// must not become a reference, which GMVDK keeps for good.
    pub fn set_quaternion(&mut self, q: Quat) {
        self.q = q;
        self.q_start = q;
        self.startup = None;
    }

    /// Values an update could leave (see `filters::holds`).
    pub(crate) fn valid(&self) -> bool {
        use super::holds;
        let r = &self.regression;
        let w = &*self.window;
        let t = &self.trust;
        let unit_interval = |x: f64| holds::within(x, 0.0, 1.0);
        holds::unit(self.q)
            && holds::unit(self.q_start)
            && holds::rate(self.bias)
            && self.a_init.map_or(true, |a| holds::accel(a.v) && a.v.norm_squared() > 0.0)
            && self.m_init.map_or(true, |m| holds::mag(m.v) && m.v.norm_squared() > 0.0)
            && holds::within(self.g0, 0.0, 2.0 * super::MAX_ACCEL)
            && self.ms_gyro >= 0.0
            && self.ms_accel >= 0.0
            && self.time >= 0.0
            && self.startup.as_ref().map_or(true, StartupMeans::valid)
            && r.n >= 0.0
            // An empty regression is the default one: the update starts one over only when
            // it holds samples.
            && (r.n > 0.0 || *r == Regression::default())
            && w.len <= WINDOW_SLOTS
            && w.head < WINDOW_SLOTS
            && unit_interval(t.alpha)
            && unit_interval(t.mu_ka)
            && unit_interval(t.mu_km)
            && unit_interval(t.mu_k)
    }

    pub(crate) fn codec(&mut self, c: &mut dyn super::state::Codec) {
        c.quat(&mut self.q);
        c.quat(&mut self.q_start);
        c.vec3(&mut self.bias);
        Reference::codec(&mut self.a_init, c);
        Reference::codec(&mut self.m_init, c);
        c.f64(&mut self.g0);
        c.f64(&mut self.ms_gyro);
        c.f64(&mut self.ms_accel);
        c.f64(&mut self.time);
        StartupMeans::codec(&mut self.startup, c);
        let r = &mut self.regression;
        for v in [&mut r.n, &mut r.t0, &mut r.st, &mut r.stt, &mut r.last_t] {
            c.f64(v);
        }
        c.vec3(&mut r.sy);
        c.vec3(&mut r.sty);
        let w = &mut *self.window;
        c.usize(&mut w.head);
        c.usize(&mut w.len);
        if w.head >= WINDOW_SLOTS || w.len > WINDOW_SLOTS {
            c.fail();
            w.head = 0;
            w.len = 0;
        }
        for i in 0..WINDOW_SLOTS {
            c.f64(&mut w.t[i]);
            c.f64(&mut w.v[i]);
        }
        c.f64(&mut self.trust.alpha);
        c.f64(&mut self.trust.mu_ka);
        c.f64(&mut self.trust.mu_km);
        c.f64(&mut self.trust.mu_k);
        c.bool(&mut self.mag_seen);
    }

    pub fn bias(&self) -> Vec3 {
        self.bias
    }

    pub fn trust(&self) -> Trust {
        self.trust
    }

    /// True when the last update had a magnetometer reading (μ values apply).
    pub fn mag_seen(&self) -> bool {
        self.mag_seen
    }

    pub fn initializing(&self) -> bool {
        self.startup.is_some()
    }

    /// The start-up attitude and references from the still period's means. True when the
    /// mean field gave the heading (a field parallel to gravity gives none: the attitude is
    /// then the accelerometer's alone).
    fn finish_startup(&mut self, s: &StartupMeans) -> bool {
        let accel = s.accel();
        let mag = s.mag();
        let with_mag = mag.and_then(|m| Frame::Enu.attitude_from(accel, Some(m)));
        let q = with_mag.or_else(|| Frame::Enu.attitude_from(accel, None)).unwrap_or(Quat::IDENTITY);
        self.q = q;
        self.q_start = q;
        self.bias = s.bias();
        self.a_init = Some(Reference::new(q.rotate(accel)));
        self.m_init = mag.map(|m| Reference::new(q.rotate(m)));
        // A period that never kept still has no stationary norm: the configured gravity.
        self.g0 = if s.moved() { self.settings.gravity } else { accel.norm() };
        with_mag.is_some()
    }

    #[inline(always)]
    pub fn update(&mut self, dt: f64, gyro: Vec3, accel: Option<Vec3>, mag: Option<Vec3>) -> Option<Step> {
        let mut step = Step::default();
        if let Some(mut s) = self.startup.clone() {
            let a = accel?;
            self.time += dt;
            // Still: within the activity scales, where stillness would reach zero.
            let still = Stillness {
                gyro: self.settings.gyro_activity,
                accel: self.settings.accel_activity,
                gravity: self.settings.gravity,
            };
            if !s.add(dt, gyro, a, mag, self.settings.init_duration, still) {
                // The readings went into the period's means (A_init, M_init).
                self.startup = Some(s);
                step.initializing = true;
                step.used_accel = true;
                step.used_mag = mag.is_some();
                return Some(step);
            }
            step.used_mag = self.finish_startup(&s);
            self.startup = None;
            step.used_accel = true;
            return Some(step);
        }
        let st = &self.settings;
        let time = self.time + dt;
        // [1]-[2]: de-biased gyroscope, prediction (7)-(8).
        let omega_b = gyro - self.bias;
        // |q + ½dt q⊗ω|² = |q|² (1 + (½dt|ω|)²) is at least 1, and for accepted samples
        // (dt ≤ 1e6 s, |ω| below 2e5 rad/s with each of the bias's components under 1e5)
        // below 1e23: in the fast range, normalised without its test. A rate that
        // overflows it (a core driven directly with an absurd one) gives NaN, which the
        // test of q_out below refuses.
        let q_g = self.q.plus_mul_pure_scaled(omega_b, 0.5 * dt).normalized_in_range();

        // α from stillness (Appendix B.1).
        let c = crate::math::one_minus_exp_neg(dt / st.activity_tau);
        let ms_gyro = self.ms_gyro + c * (omega_b.norm_squared() - self.ms_gyro);
        let mut g0 = self.g0;
        let mut ms_accel = self.ms_accel;
        let a_norm = accel.map_or(0.0, Vec3::norm);
        if accel.is_some() {
            // A known start skipped the start-up period: the configured gravity is the
            // stationary norm (one reading could be a glitch, and a wrong g0 would keep
            // α at its floor for good).
            if g0 == 0.0 {
                g0 = st.gravity;
            }
            let dev = a_norm - g0;
            ms_accel += c * (dev * dev - ms_accel);
        }
        let activity = 0.5
            * (ms_gyro / (st.gyro_activity * st.gyro_activity)
                + ms_accel / (st.accel_activity * st.accel_activity));
        let stillness = (1.0 - activity).max(0.0);
        let alpha1 = stillness * st.slope_alpha + 1.0 - st.slope_alpha;
        let alpha = ((alpha1 + alpha1.abs()) / 2.0).min(1.0);
        // The μ values change only with a magnetometer reading.
        let mut trust = None;

        // [3]-[6]: accelerometer pipeline. The first reading's references are kept at the
        // commit below (a failed step leaves none).
        let mut a_new = None;
        // The accelerometer reading and its reference, for a first M_init below.
        let mut a_pair = None;
        // (10)-(13): q_ga = q_g ⊗ Δq_a. Kept as Δq_a: (14), q_sa = SLERP(q_g, q_ga, α), is
        // q_g ⊗ SLERP(1, Δq_a, α) ([`slerp_from_identity`]), formed below with (17).
        let dq_a = match accel {
            Some(a0) => {
                step.used_accel = true;
                let a_ref = match self.a_init {
                    Some(r) => r,
                    None => *a_new.insert(Reference::new(Vec3::new(0.0, 0.0, st.gravity))),
                };
                a_pair = Some((a0, a_ref));
                let a_pred = q_g.rotate_inverse(a_ref.v); // (9)
                Some(eq10_to_12_with_norms(a0, a_norm, a_pred, a_ref.norm)) // (10)-(12); (13) below
            }
            None => None,
        };

        // [3']-[6']: magnetometer pipeline with μ_K (Appendix B.2).
        let mut m_new = None;
        let mut mu1 = None;
        // SLERP(1, Δq_m, μ_K), with q_sm = q_g ⊗ it.
        // After a known start, M_init waits for a sample whose accelerometer reads gravity
        // (as a still one does): its dip is taken against that reading.
        let first_ok = self.m_init.is_some() || (a_norm - st.gravity).abs() <= GRAVITY_STILL * st.gravity;
        let sm = match (mag, a_pair) {
            (Some(m0), Some((a0, a_ref))) if first_ok => {
                step.used_mag = true;
                let m_ref = match self.m_init {
                    Some(r) => r,
                    None => *m_new.insert(first_field(self.q, a0, a_ref.v, m0)),
                };
                // |m0i| = |m0| below: the rotation keeps the norm, which (12) needs too.
                let m0i = self.q.rotate(m0); // (18), previous q_out
                let m0_norm = m0.norm();
                let cos_l = (m0i.dot(m_ref.v) / (m0_norm * m_ref.norm)).clamp(-1.0, 1.0);
                let lambda = eq19_lambda(cos_l); // (19)
                let mu_ka = (1.0 - st.slope_muk * lambda).max(0.0); // (20)
                let mu_km = (1.0 - (m0_norm / m_ref.norm) * lambda).max(0.0); // (21)-(22)
                let m1 = 0.5 * (mu_ka + mu_km); // (23)
                let mu2 = self.window.peek(time, m1, st.mu_window);
                let mu_k = mu2 * alpha; // (24)
                trust = Some(Trust { alpha, mu_ka, mu_km, mu_k });
                mu1 = Some(m1);
                let m_pred = q_g.rotate_inverse(m_ref.v);
                let dq_m = eq10_to_12_with_norms(m0, m0_norm, m_pred, m_ref.norm); // q_gm = q_g ⊗ Δq_m
                Some(slerp_from_identity_for_half(dq_m, mu_k))
            }
            _ => None,
        };

        // [7]: second-tier SLERP (17), q_out = SLERP(q_sm, q_sa, ½)
        //   = q_g ⊗ SLERP(SLERP(1, Δq_m, μ_K), SLERP(1, Δq_a, α), ½) (left invariance):
        // one product with q_g instead of one per pipeline.
        let q_out = match (dq_a, sm) {
            (Some(dq_a), Some(sm)) => q_g * slerp_half(sm, slerp_from_identity_for_half(dq_a, alpha)),
            // No magnetometer: q_sm = q_g, so q_sa and q_out lie on one arc from q_g and
            // SLERP(q_g, SLERP(q_g, q_ga, α), ½) = SLERP(q_g, q_ga, α/2): one SLERP.
            (Some(dq_a), None) => q_g * slerp_from_identity(dq_a, 0.5 * alpha),
            // No accelerometer: q_sa = q_sm = q_g.
            (None, _) => q_g,
        };
        // q_out is unit when it is finite (a product of unit quaternions): its components'
        // sum is non-finite exactly when one of them is, with no overflow from finite ones.
        if ((q_out.w + q_out.x) + (q_out.y + q_out.z)) * 0.0 != 0.0 {
            return None;
        }

        // Commit. Step [1]'s de-biasing: regression over static runs.
        if alpha >= st.static_alpha && step.used_accel {
            self.regression.add(time, gyro);
            if self.regression.duration() >= st.bias_window {
                let bias = self.regression.value_at_end();
                if bias.is_finite() {
                    self.bias = bias;
                }
                self.regression = Regression::default();
            }
        } else if self.regression.n != 0.0 {
            // Started over only when it holds samples: eleven stores on every moving step
            // otherwise.
            self.regression = Regression::default();
        }
        if let Some(m1) = mu1 {
            self.window.push(time, m1, st.mu_window);
        }
        self.mag_seen = mu1.is_some();
        self.q = q_out;
        self.time = time;
        self.g0 = g0;
        self.ms_gyro = ms_gyro;
        self.ms_accel = ms_accel;
        if a_new.is_some() {
            self.a_init = a_new;
        }
        if m_new.is_some() {
            self.m_init = m_new;
        }
        match trust {
            Some(t) => self.trust = t,
            None => self.trust.alpha = alpha,
        }
        Some(step)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The series weights of [`slerp`] against the readable form, [`slerp_by_acos`], for
    /// arcs (half the rotation angle) from 5e-7 to 0.15 rad and h in [0, 1], some past
    /// the series' range: each component within 4e-16.
    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn slerp_series_is_the_acos_form() {
        let mut u = crate::math::test_uniform(9);
        let mut r = || 0.5 * (u() + 1.0);
        let (mut series, mut worst) = (0, 0.0f64);
        for _ in 0..20000 {
            let q1 = Quat::new(r() - 0.5, r() - 0.5, r() - 0.5, r() - 0.5).normalized();
            let axis = Vec3::new(r() - 0.5, r() - 0.5, r() - 0.5);
            let angle = 10f64.powf(-6.0 + 5.48 * r()); // rotation angle; the arc is half of it
            let q2 = q1 * Quat::from_axis_angle(axis, angle);
            let h = r();
            let cos = q1.dot(q2);
            if cos > 1.0 - 1e-12 {
                continue;
            }
            series += usize::from((1.0 - cos) * (1.0 + cos) < 1.0 / 400.0);
            let (a, b) = (slerp(q1, q2, h), slerp_by_acos(q1, q2, cos, h));
            for (x, y) in [(a.w, b.w), (a.x, b.x), (a.y, b.y), (a.z, b.z)] {
                worst = worst.max((x - y).abs());
            }
        }
        assert!(series > 10000 && series < 19000, "the series covered {series} cases");
        // Extrapolating (h beyond 1) takes (hω)² past the series' range: the readable form.
        let q1 = Quat::from_axis_angle(Vec3::new(0.3, -0.2, 0.9), 0.4);
        let q2 = q1 * Quat::from_axis_angle(Vec3::new(1.0, 0.5, 0.0), 0.08);
        for h in [1.5, 3.0, 10.0] {
            let cos = q1.dot(q2);
            let (a, b) = (slerp(q1, q2, h), slerp_by_acos(q1, q2, cos, h));
            for (x, y) in [(a.w, b.w), (a.x, b.x), (a.y, b.y), (a.z, b.z)] {
                worst = worst.max((x - y).abs());
            }
        }
        assert!(worst <= 4e-16, "{worst}");
    }

    /// Left invariance as the update uses it: `SLERP(q_g, q_g ⊗ Δq, h)` (the paper's
    /// (14)) against `q_g ⊗ SLERP(1, Δq, h)`, and (17)'s half SLERP of two such (formed as
    /// the update forms them, with [`slerp_from_identity_for_half`]'s ends), over
    /// random q_g and Δq from 1e-9 rad to a half turn (both sides of the series' range,
    /// the linear end and the flip of a negative Δq.w), h in [0, 1]: each component
    /// within 1e-15.
    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn slerp_from_identity_is_slerp_from_q_g() {
        let mut u = crate::math::test_uniform(17);
        let mut unit = || Quat::new(u(), u(), u(), u()).normalized();
        let mut v = crate::math::test_uniform(18);
        let (mut worst, mut worst_half) = (0.0f64, 0.0f64);
        for i in 0..20000 {
            let q_g = unit();
            let angle = 10f64.powf(-9.0 + 9.5 * 0.5 * (v() + 1.0)).min(3.0);
            let mut dq = Quat::from_axis_angle(Vec3::new(v(), v(), v()), angle);
            if i % 3 == 0 {
                dq = dq.scale(-1.0);
            }
            let h = 0.5 * (v() + 1.0);
            let (paper, ours) = (slerp(q_g, q_g * dq, h), q_g * slerp_from_identity(dq, h));
            let dm = Quat::from_axis_angle(Vec3::new(v(), v(), v()), 0.3 * angle);
            let half_paper = slerp_half(slerp(q_g, q_g * dm, 1.0 - h), paper);
            // The update's form: the ends normalised only where they are not unit to rounding.
            let half_ours = q_g
                * slerp_half(slerp_from_identity_for_half(dm, 1.0 - h), slerp_from_identity_for_half(dq, h));
            for (a, b, w) in [(paper, ours, &mut worst), (half_paper, half_ours, &mut worst_half)] {
                for (x, y) in [(a.w, b.w), (a.x, b.x), (a.y, b.y), (a.z, b.z)] {
                    *w = w.max((x - y).abs());
                }
            }
        }
        assert!(worst <= 1e-15 && worst_half <= 1e-15, "{worst:e} {worst_half:e}");
    }

    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn slerp_half_is_slerp_at_one_half() {
        let a = Quat::from_axis_angle(Vec3::new(1.0, 0.0, 0.0), 0.2);
        for (axis, angle) in [
            (Vec3::new(0.0, 1.0, 1.0), 1.0),
            (Vec3::new(0.3, -1.0, 0.2), 2.9),
            (Vec3::new(0.0, 0.0, 1.0), 1e-7),
        ] {
            let b = Quat::from_axis_angle(axis, angle) * a;
            for b in [b, b.scale(-1.0)] {
                let (half, general) = (slerp_half(a, b), slerp(a, b, 0.5));
                assert!(half.dot(general) > 1.0 - 1e-15, "{half:?} {general:?}");
            }
        }
    }
    use crate::filters::complementary::rotation_of;

    fn exact(q: Quat, w: Vec3, dt: f64) -> Quat {
        q * rotation_of(w, dt)
    }

    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn slerp_matches_eq16_and_its_endpoints() {
        let a = Quat::from_axis_angle(Vec3::new(1.0, 0.0, 0.0), 0.2);
        let b = Quat::from_axis_angle(Vec3::new(0.0, 1.0, 1.0), 1.0);
        assert!(slerp(a, b, 0.0).angle_to(a) < 1e-12);
        assert!(slerp(a, b, 1.0).angle_to(b) < 1e-12);
        // Eq. (16) by hand at h = 0.3.
        let omega = a.dot(b).acos();
        let hand = a.scale((0.7 * omega).sin() / omega.sin()) + b.scale((0.3 * omega).sin() / omega.sin());
        assert!(slerp(a, b, 0.3).angle_to(hand) < 1e-12);
        // The midpoint is equally far from both.
        let m = slerp(a, b, 0.5);
        assert!((m.angle_to(a) - m.angle_to(b)).abs() < 1e-12);
        // Shorter arc for sign-flipped inputs.
        assert!(slerp(a, b.scale(-1.0), 0.3).angle_to(hand) < 1e-12);
        // Near h = 1, where the first weight is a difference of two terms near cos ω,
        // and for arcs from 1e-5 rad to nearly half a turn: eq. (16) by hand.
        for (axis, angle) in [
            (Vec3::new(0.0, 1.0, 1.0), 1.0),
            (Vec3::new(0.3, -1.0, 0.2), 1e-5),
            (Vec3::new(1.0, 2.0, -0.5), 3.0),
        ] {
            let b = Quat::from_axis_angle(axis, angle) * a;
            let omega = a.dot(b).acos();
            for h in [0.001, 0.3, 0.999] {
                let (w1, w2) = ((1.0 - h) * omega, h * omega);
                let hand = (a.scale(w1.sin() / omega.sin()) + b.scale(w2.sin() / omega.sin())).normalized();
                assert!(slerp(a, b, h).dot(hand) > 1.0 - 1e-15, "angle {angle}, h {h}");
            }
        }
    }

    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn without_a_magnetometer_the_two_slerps_are_one() {
        // (14) then (17) with q_sm = q_g, against the single SLERP the update uses.
        let q_g = Quat::from_axis_angle(Vec3::new(0.3, 1.0, 0.2), 0.5);
        for (axis, angle) in [(Vec3::new(1.0, -0.4, 0.2), 0.03), (Vec3::new(0.0, 0.3, 1.0), 1.2)] {
            let q_ga = q_g * Quat::from_axis_angle(axis, angle);
            for q_ga in [q_ga, q_ga.scale(-1.0)] {
                for alpha in [0.0, 0.2, 0.7, 1.0] {
                    let two = slerp(q_g, slerp(q_g, q_ga, alpha), 0.5);
                    let one = slerp(q_g, q_ga, 0.5 * alpha);
                    assert!(two.angle_to(one) < 1e-12, "{alpha} {angle}");
                }
            }
        }
    }

    /// The largest component difference of two forms of (10)-(12), over `1 + 1/w` with w
    /// the second's scalar part: both lose to cancellation in `1 + cos` what they lose in
    /// the scalar part, an error of about ε/(2w) for a rotation whose scalar part is w.
    fn scaled_difference(ours: Quat, other: Quat) -> f64 {
        let d = [ours.w - other.w, ours.x - other.x, ours.y - other.y, ours.z - other.z];
        d.iter().fold(0.0f64, |m, x| m.max(x.abs())) / (1.0 + 1.0 / other.w)
    }

    /// [`eq10_to_12`] against `Quat::from_two_vectors` over random pairs of lengths from
    /// 1e-150 to 1e12, near-opposite and opposite pairs included: the same rotation, each
    /// component within 5e-16 (1 + 1/w) for a rotation of scalar part w (both normalised,
    /// the sign fixed by the positive scalar part).
    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn eq10_to_12_is_from_two_vectors() {
        let mut u = crate::math::test_uniform(43);
        let mut worst = 0.0f64;
        for i in 0..20000 {
            let mut len = || 10f64.powf(-150.0 + 162.0 * 0.5 * (u() + 1.0));
            let (l0, l1) = (len(), len());
            let v0 = Vec3::new(u(), u(), u()) * l0;
            let v = match i % 4 {
                0 => v0 * (-l1 / l0),
                1 => (v0 * -1.0 + Vec3::new(u(), u(), u()) * (1e-9 * l0)) * (l1 / l0),
                _ => Vec3::new(u(), u(), u()) * l1,
            };
            worst = worst.max(scaled_difference(eq10_to_12(v0, v), Quat::from_two_vectors(v0, v)));
        }
        assert!(worst <= 5e-16, "{worst:e}");
    }

    /// (10)-(12)'s normalisation by `2 |v₀||v̂| q₀`: within 120° of each other the result
    /// is unit within 3 ulp (lengths 1e-150 to 1e12, angles up to the bound); past 120°
    /// it is `Quat::from_two_vectors`' own bits.
    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn eq10_to_12_normalises_by_the_product_within_120_degrees() {
        let mut u = crate::math::test_uniform(47);
        let (mut worst, mut past) = (0.0f64, 0);
        for _ in 0..20000 {
            let mut len = || 10f64.powf(-150.0 + 162.0 * 0.5 * (u() + 1.0));
            let (l0, l1) = (len(), len());
            let v0 = Vec3::new(u(), u(), u()) * l0;
            let v = Vec3::new(u(), u(), u()) * l1;
            let dq = eq10_to_12(v0, v);
            if v0.normalized().dot(v.normalized()) > -0.5 + 1e-12 {
                worst = worst.max((dq.norm_squared() - 1.0).abs());
            } else if v0.normalized().dot(v.normalized()) < -0.5 - 1e-12 {
                past += 1;
                assert_eq!(dq, Quat::from_two_vectors(v0, v), "{v0:?} {v:?}");
            }
        }
        assert!(worst <= 6.0 * f64::EPSILON, "{worst:e}");
        assert!(past > 3000, "{past} pairs past 120 degrees");
    }

    /// The update's (10)-(12) with the reference's stored norm in place of the rotated
    /// prediction's: the same rotation to rounding, each component within 8e-16 (1 + 1/w)
    /// (the rotation's rounding of |v̂|, a few ulps, and each form's own; 4.5e-16 seen),
    /// over random orientations, references and readings (lengths 1e-3 to 1e3).
    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn the_references_norm_stands_for_the_predictions() {
        let mut u = crate::math::test_uniform(44);
        let mut worst = 0.0f64;
        for _ in 0..20000 {
            let q_g = Quat::new(u(), u(), u(), u()).normalized();
            let (l0, l1) = (10f64.powf(3.0 * u()), 10f64.powf(3.0 * u()));
            let r = Reference::new(Vec3::new(u(), u(), u()) * l0);
            let v0 = Vec3::new(u(), u(), u()) * l1;
            let v = q_g.rotate_inverse(r.v);
            let ours = eq10_to_12_with_norms(v0, v0.norm(), v, r.norm);
            worst = worst.max(scaled_difference(ours, eq10_to_12(v0, v)));
        }
        assert!(worst <= 8e-16, "{worst:e}");
    }

    /// (19)'s series form against libm's `acos` for cosines from 1 down past the series'
    /// range (λ to 8°): within 3ε relative to λ (3 to 6 units in its last place); exact at
    /// λ = 0.
    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn eq19_series_is_the_arccosine() {
        assert_eq!(eq19_lambda(1.0), 0.0);
        let mut u = crate::math::test_uniform(45);
        for i in 0..100_000 {
            // Angles spread over 8e-8 to 8 degrees (1.4e-9 to 0.14 rad) on a log scale, and
            // a few cosines a few ulps below 1.
            let c = if i < 100 {
                1.0 - i as f64 * f64::EPSILON / 2.0
            } else {
                libm::cos(8f64.to_radians() * 10f64.powf(-8.0 * 0.5 * (u() + 1.0)))
            };
            let (ours, acos) = (eq19_lambda(c), libm::acos(c));
            assert!((ours - acos).abs() <= 3.0 * f64::EPSILON * acos, "cos {c}: {ours} vs {acos}");
        }
    }

    #[test]
    fn eq10_to_13_align_the_predicted_gravity_with_the_measurement() {
        let q_g = Quat::from_axis_angle(Vec3::new(0.3, 1.0, 0.2), 0.5);
        let a_init = Vec3::new(0.0, 0.0, 9.81);
        let a0 = Vec3::new(1.0, -2.0, 9.5);
        let q_ga = q_g * Quat::from_two_vectors(a0, q_g.rotate_inverse(a_init));
        let mapped = q_ga.rotate_inverse(a_init).normalized();
        assert!((mapped - a0.normalized()).norm() < 1e-12);
        // Paper form (11)-(12): H(a0 × a, |a0||a| + a0·a), normalised, is the same rotation.
        let a = q_g.rotate_inverse(a_init);
        let v = a0.cross(a);
        let paper = Quat::new(a0.norm() * a.norm() + a0.dot(a), v.x, v.y, v.z).normalized();
        assert!(paper.angle_to(Quat::from_two_vectors(a0, a)) < 1e-12);
        assert_eq!(paper, eq10_to_12(a0, a));
    }

    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn running_minimum_covers_exactly_the_time_window() {
        let mut w = MinWindow::new();
        let dt = 0.01;
        let mut mins = Vec::new();
        for i in 0..200 {
            let v = if i == 50 { 0.1 } else { 1.0 };
            mins.push(w.push(i as f64 * dt, v, 0.4));
        }
        // The dip at t = 0.50 s holds for samples with t - 0.4 < 0.5: t < 0.9.
        assert_eq!(mins[49], 1.0);
        assert_eq!(mins[50], 0.1);
        assert_eq!(mins[89], 0.1);
        assert_eq!(mins[90], 1.0);
        // At 10 kHz the slots still suffice (entries share slots at 0.4 ms).
        let mut fast = MinWindow::new();
        for i in 0..100_000 {
            let m = fast.push(i as f64 * 1e-4, 1.0 - (i as f64) * 1e-6, 0.4);
            assert!(m <= 1.0);
        }
        assert!(fast.len <= 1001);
    }

    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn reset_equals_a_new_filter() {
        let mut f = Gmvdk::new(GmvdkSettings::default());
        f.set_quaternion(Quat::from_axis_angle(Vec3::new(1.0, 0.0, 0.0), 0.3));
        for _ in 0..50 {
            f.update(
                0.01,
                Vec3::new(0.1, 0.0, 0.0),
                Some(Vec3::new(0.0, 1.0, 9.7)),
                Some(Vec3::new(5.0, 20.0, -40.0)),
            )
            .unwrap();
        }
        f.reset();
        let fresh = Gmvdk::new(GmvdkSettings::default());
        // The window's stale slots do not matter: len is 0.
        assert_eq!((f.window.len, f.window.head), (0, 0));
        f.window = fresh.window.clone();
        assert_eq!(f, fresh);
    }

    /// Moving steps leave an empty regression the default one (the update starts it over
    /// only when it holds samples), a still one fills it, and `valid` refuses an empty
    /// regression that is not the default, which the update would keep.
    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn an_empty_regression_is_the_default_one() {
        let mut f = Gmvdk::new(GmvdkSettings::default());
        let accel = Some(Vec3::new(0.0, 0.0, 9.81));
        for _ in 0..200 {
            f.update(0.01, Vec3::ZERO, accel, None).unwrap();
        }
        assert!(f.startup.is_none() && f.regression.n > 0.0);
        for i in 0..50 {
            f.update(0.01, Vec3::new(2.0, -1.0, 0.5 * i as f64), accel, None).unwrap();
            assert_eq!(f.regression, Regression::default());
        }
        assert!(f.valid());
        f.regression.st = 1.0;
        assert!(!f.valid());
    }

    #[test]
    fn regression_recovers_a_linear_drift() {
        let mut r = Regression::default();
        for i in 0..100 {
            let t = 5.0 + i as f64 * 0.01;
            r.add(t, Vec3::new(0.01 + 0.002 * t, -0.02, 0.0));
        }
        let end = r.value_at_end();
        assert!((end.x - (0.01 + 0.002 * 5.99)).abs() < 1e-12, "{end:?}");
        assert!((end.y + 0.02).abs() < 1e-15);
    }

    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn still_sensor_trusts_the_accelerometer_and_converges() {
        let mut f = Gmvdk::new(GmvdkSettings::default());
        let truth = Quat::from_axis_angle(Vec3::new(0.2, 0.4, 1.0), 0.8);
        f.set_quaternion(truth);
        let accel = truth.rotate_inverse(Vec3::new(0.0, 0.0, 9.81));
        let mag = truth.rotate_inverse(Vec3::new(0.0, 20.0, -40.0));
        f.update(0.01, Vec3::ZERO, Some(accel), Some(mag)).unwrap();
        // Knock the estimate 0.2 rad off. Still and undisturbed, the first step removes most
        // of the tilt; heading follows at a few percent per step, because the
        // magnetometer's shortest-arc correction has a vertical component of only
        // cos²(dip) (0.2 here); the error falls steadily and both trusts return to 1.
        f.q = exact(truth, Vec3::new(1.0, 0.0, 0.0), 0.2);
        let mut errors = Vec::new();
        for _ in 0..400 {
            f.update(0.01, Vec3::ZERO, Some(accel), Some(mag)).unwrap();
            errors.push(f.quaternion().angle_to(truth));
        }
        assert!(errors[0] < 0.1, "{}", errors[0]);
        assert!(errors.windows(2).all(|w| w[1] <= w[0] + 1e-15));
        assert!(errors[399] < 1e-6, "{}", errors[399]);
        let t = f.trust();
        assert!(t.alpha > 0.99 && t.mu_k > 0.99, "{t:?}");
    }

    /// Started from a known attitude that is wrong (the identity, or any the host gives)
    /// while the sensor lies tilted, the references come from the first readings: M_init
    /// must keep the field's measured dip against A_init (the paper takes both at one
    /// still instant), or no attitude matches both and the double SLERP settles between
    /// them. Still and undisturbed, every start must reach the true inclination: within
    /// 0.5° after 60 s. (The heading stays the start's: M_init's horizontal direction
    /// defines north, as the paper's start-up pose defines its inertial frame.)
    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn a_wrong_known_start_reaches_the_truth() {
        let truth = Quat::from_axis_angle(Vec3::new(0.3, -0.8, 0.2), 0.5);
        let accel = truth.rotate_inverse(Vec3::new(0.0, 0.0, 9.81));
        let mag = truth.rotate_inverse(Vec3::new(0.0, 20.0, -40.0));
        let starts = [
            Quat::IDENTITY,
            Quat::from_axis_angle(Vec3::new(1.0, 0.0, 0.0), 1.0),
            Quat::new(-18.5, 31.25, -18.5, 10.0).normalized(),
            truth * Quat::from_axis_angle(Vec3::new(0.0, 1.0, 0.0), 0.3),
        ];
        for start in starts {
            let mut f = Gmvdk::new(GmvdkSettings::default());
            f.set_quaternion(start);
            for _ in 0..6000 {
                f.update(0.01, Vec3::ZERO, Some(accel), Some(mag)).unwrap();
            }
            let up = f.quaternion().rotate_inverse(Vec3::new(0.0, 0.0, 1.0));
            let error = up.dot(accel.normalized()).clamp(-1.0, 1.0).acos().to_degrees();
            println!("start {start:?}: inclination {error:.3} deg");
            assert!(error < 0.5, "start {start:?}: inclination {error} deg");
        }
    }
}

/// The common lifecycle's view of this kind (see [`super::estimator::Estimator`]).
mod estimator_impl {
    use super::*;
    use crate::filters::diag;
    use crate::filters::estimator::estimator;
    use crate::filters::Diagnostics;

    estimator!(impl for Gmvdk { settings: GmvdkSettings, native: Enu, own_startup: true, diagnostics: GYRO_BIAS | ALPHA | MU_KA | MU_KM | MU_K } {
        fn configure(&mut self, settings: GmvdkSettings) {
            Gmvdk::configure(self, settings);
        }

        fn heap_bytes(&self) -> usize {
            core::mem::size_of::<MinWindow>()
        }

        fn starting(&self) -> bool {
            self.startup.as_ref().is_some_and(StartupMeans::begun)
        }

        fn restart(&mut self, settings: GmvdkSettings) {
            // Keeps the boxed μ window: no allocation.
            self.settings = settings;
            self.reset();
        }

        fn absolute_quaternion(&self) -> Quat {
            Gmvdk::absolute_quaternion(self)
        }

        fn relative(&self) -> bool {
            self.settings.relative_output.on()
        }

        #[inline(always)]
        fn update(&mut self, dt: f64, gyro: Vec3, accel: Option<Vec3>, mag: Option<Vec3>) -> Option<Step> {
            match mag {
                None => gmvdk_update_without_mag(self, dt, gyro, accel),
                Some(m) => gmvdk_update_with_mag(self, dt, gyro, accel, m),
            }
        }

        fn diagnose(&self, d: &mut Diagnostics) {
            d.gyro_bias = self.bias();
            let t = self.trust();
            d.alpha = t.alpha;
            if self.mag_seen() {
                d.mu_ka = t.mu_ka;
                d.mu_km = t.mu_km;
                d.mu_k = t.mu_k;
            } else {
                d.present &= !(diag::MU_KA | diag::MU_KM | diag::MU_K);
            }
        }
    });
}

/// GMVDK's update without a magnetometer reading, in the widest copy the CPU has
/// (crate::isa::widest). Out of line: its large frame, inlined into a caller, made that
/// caller save six registers and set up the frame before any work. One copy per case:
/// each is compiled for its own path, so the magnetometer pipeline's code does not shape
/// the registers of the accelerometer-only step (a change to the first moved the
/// second's count when they shared a function).
#[inline(never)]
fn gmvdk_update_without_mag(f: &mut Gmvdk, dt: f64, gyro: Vec3, accel: Option<Vec3>) -> Option<Step> {
    crate::isa::widest(
        #[inline(always)]
        || f.update(dt, gyro, accel, None),
    )
}

/// [`gmvdk_update_without_mag`] with a magnetometer reading.
#[inline(never)]
fn gmvdk_update_with_mag(f: &mut Gmvdk, dt: f64, gyro: Vec3, accel: Option<Vec3>, mag: Vec3) -> Option<Step> {
    crate::isa::widest(
        #[inline(always)]
        || f.update(dt, gyro, accel, Some(mag)),
    )
}
