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

use crate::filters::kinds::startup::{stationary_norm, StartupMeans, Stillness, GRAVITY_STILL};
use crate::filters::params::{settings, Switch};
use crate::filters::pipeline::estimator::Step;
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

mod slerp;
mod trust;
use slerp::*;
pub use slerp::{eq10_to_12, slerp, slerp_from_identity, slerp_half};
use trust::*;

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
    fn codec(r: &mut Option<Reference>, c: &mut dyn crate::filters::state::Codec) {
        let mut v = r.map(|r| r.v);
        c.opt_vec3(&mut v);
        *r = v.map(Reference::new);
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
    /// refers to is kept), the static-run regression started over, the bias kept, but for
    /// the rest watch's re-acquisition of a still sensor, where the bias is the still
    /// gyroscope reading: a wrong bias spins the de-biased rate, α then stays 0 and the
    /// static runs that would correct it never come. The gap counts as time, so the μ
    /// window forgets the readings before it.
    pub(crate) fn reacquire(&mut self, r: &crate::filters::pipeline::estimator::Reacquisition) -> bool {
        let (q, used_mag) = r.plain();
        self.q = q;
        if let Some(g) = r.still {
            self.bias = g;
        }
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
        use crate::filters::state::holds;
        let r = &self.regression;
        let w = &*self.window;
        let t = &self.trust;
        let unit_interval = |x: f64| holds::within(x, 0.0, 1.0);
        holds::unit(self.q)
            && holds::unit(self.q_start)
            && holds::rate(self.bias)
            && self.a_init.map_or(true, |a| holds::accel(a.v) && a.v.norm_squared() > 0.0)
            && self.m_init.map_or(true, |m| holds::mag(m.v) && m.v.norm_squared() > 0.0)
            && holds::within(self.g0, 0.0, 2.0 * crate::filters::pipeline::sample::MAX_ACCEL)
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

    pub(crate) fn codec(&mut self, c: &mut dyn crate::filters::state::Codec) {
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
mod tests;

/// The common lifecycle's view of this kind (see [`crate::filters::pipeline::estimator::Estimator`]).
mod estimator_impl {
    use super::*;
    use crate::filters::diag;
    use crate::filters::pipeline::estimator::estimator;
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
