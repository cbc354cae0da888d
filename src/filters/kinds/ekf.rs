//! Kim & Golnaraghi's quaternion extended Kalman filter: state [q, ω, δ], accelerometer
//! as rotated gravity, gyroscope as ω + δ; with an optional magnetometer heading
//! measurement that moves heading only.
//!
//! Source: A. Kim, M. F. Golnaraghi, "A Quaternion-Based Orientation Estimation Algorithm
//! Using an Inertial Measurement Unit", IEEE PLANS 2004
//! (`shared/papers/kim-golnaraghi-2004-quaternion-ekf.txt`). Equation numbers are the
//! paper's.
//!
//! - State (6): `x = [q, ω, δ]`, `q = [q0 q1 q2 q3]`. With (7) and (8),
//!   `C_o^b = R(q)ᵀ` and `q̇ = ½ q ⊗ [0, ω]`: `q` is orient's sensor-to-earth quaternion.
//!   (13) has the accelerometer read `C_o^b [0 0 −g]ᵀ` at rest, so the ground frame's z
//!   points down: the native frame is North-East-Down (north from the magnetometer
//!   heading measurement when there is one).
//! - Process (8)-(10). The paper writes (9)-(10) with `+1/τ`, which is unstable; a
//!   first-order Markov process needs `−1/τ`, implemented here.
//! - Discretisation: over one step of length dt, `ω⁺ = e^{−dt/τ_ω} ω + w_ω`,
//!   `δ⁺ = e^{−dt/τ_δ} δ + w_δ`, and `q⁺ = q ⊗ exp(ω⁺ dt/2)` (exact for a rate constant
//!   over the step): ω⁺ is the rate over the interval ending at the new sample, which is
//!   what a gyroscope sample reports, so the gyroscope corrects q in the same update
//!   instead of one sample late (a 3.5 ms lag at BROAD's rate, about 1° at 5 rad/s).
//!   Process noise: the exact discrete variance of each Markov process,
//!   `σ²(1 − e^{−2dt/τ})` with σ its stationary standard deviation (the paper sets the ω
//!   process noise "in relation to the limit of the magnitude" of the motion:
//!   `omega_std`); w_ω reaches q through the exponential map's Jacobian.
//! - Jacobians are analytic, including the derivative of the exponential map.
//! - Measurement (11)-(13): `z = [f, ω_IMU]`, `f = g (2q0q2 − 2q1q3, −2q0q1 − 2q2q3,
//!   −q0² + q1² + q2² − q3²)`, `ω_IMU = ω + δ`. Noise from the paper's sensor data:
//!   gyroscope 0.05 °/s/√Hz, accelerometer 32 µg/√Hz, as variances `N²/(2 dt)` (white
//!   noise over the Nyquist band).
//! - Linear acceleration: the paper tolerates "a modicum" of it. Here the accelerometer
//!   enters as a direction (scaled to length g: a norm different from g says nothing
//!   about attitude and would otherwise pull on the quaternion's norm), with variance
//!   `N²/(2dt) + (σ_motion² + (|f| − g)²)·2τ_m/dt`: a standing allowance for hand-held
//!   motion plus the squared norm deviation (a lower bound on the current linear
//!   acceleration), both scaled by the number of samples one linear-acceleration episode
//!   spans (`2τ_m/dt`, the white-noise equivalent of a first-order Markov process with
//!   correlation time τ_m), since linear acceleration is low-frequency, not white.
//!   Sustained translation (BROAD trial 15) outlasts that allowance, and the
//!   accelerometer then leaks into the drift δ (δ_z ran to -0.24 rad/s there, 12 times
//!   its prior standard deviation) and turns the estimate. So the variance is also
//!   bounded below by the innovation's own recent power (`accel_adapt_tau`, the
//!   innovation-based adaptive noise of adaptive Kalman filtering), colour-scaled the
//!   same way: while the model keeps mispredicting the accelerometer, it trusts it less.
//!   Trial 15 goes from 70.95° to 11.8°, the 9D mean from 16.99° to 5.82°; 0 turns it
//!   off and gives the fixed-noise filter.
//! - Update: R is diagonal, so the accelerometer's three rows and then the gyroscope's
//!   three are absorbed as two batches (the same posterior as six rows in turn, or as
//!   one batch: the gyroscope rows are linear), each as `P − V Vᵀ` with `V = U L⁻ᵀ`,
//!   `S = L Lᵀ`, the Joseph form's value for the optimal gain; P is kept by blocks so
//!   no product touches a structural zero; quaternion renormalised. A test checks the
//!   result against the dense textbook update (F P Fᵀ, batch Joseph, Cholesky) to 1e-12.
//! - Magnetometer (the paper's proposed extension): a heading measurement. The field is
//!   rotated into the earth frame with the predicted q; its horizontal direction `ψ_m`
//!   should be north, so the innovation is `−ψ_m`. The gain is restricted to a rotation
//!   about the earth's vertical (`q ← exp(δψ ẑ/2) ⊗ q`) and to no other state, so
//!   magnetic errors move heading only; Joseph form keeps the covariance consistent with
//!   this restricted gain. Magnetic disturbances are low-frequency as well, so the
//!   heading variance is scaled by `2τ_ψ/dt` in the same way, and bounded below by the
//!   heading innovation's recent power (`heading_adapt_tau`): near a magnet the
//!   innovation grows and the field is trusted less (trial 32: 25.3° to 2.8°).
//! - Gross inconsistencies (accepted input the model (9)-(13) cannot produce: gyroscope
//!   glitches below the 1e4 rad/s bound, a wrong attitude after a clipped spin). Each is
//!   a normalised-innovation-squared test with bound 16 (4 standard deviations):
//!   - gyroscope rows (12): `ν_i = ω_IMU,i − (a_ω ω_i + a_δ δ_i)` against its predicted
//!     variance `a_ω² P_ωω + 2 a_ω a_δ P_ωδ + a_δ² P_δδ + q_ω + q_δ + r_g` (the first
//!     three terms, a variance, taken as at least zero, so a reading within
//!     `16 (q_ω + q_δ + r_g)` passes without reading P). A reading
//!     that fails it re-initialises ω_i from the reading (`a_ω ω_i + a_δ δ_i = ω_IMU,i`,
//!     ω_i uncorrelated, variance `r_g/a_ω²`) before the step, so the drift δ, whose
//!     process (10) allows only `drift_std`, takes no share of a rate jump (9) does not
//!     allow either. Tested against the *predicted* rate: a reading held at 9999 rad/s
//!     fails on every sample, as (9) decays ω towards zero (before: δ reached 0.8
//!     rad/s and the estimate kept turning). BROAD's EKF 9D and 6D* means are
//!     unchanged with it.
//!   - gravity rows (13), at detected rest only (`rest_rate_std` set): f is gravity
//!     alone there, so `|ν|²` beyond 16 (tr(H P Hᵀ) + 3 r) is the attitude's error:
//!     P_qq ← P_qq + (σ²/4)(I − q qᵀ) with `σ² = (|ν|² − tr(H P Hᵀ) − 3r)/(2g²)`, an
//!     error of variance σ² about each axis (covariance matching), and the adaptive floor
//!     is not applied at rest. In motion the same test failed 381 times on BROAD and
//!     doubled the EKF's 9D error (5.82° to 10.17°): there a large innovation is as
//!     likely linear acceleration, so it is left to the adaptive floor.
//! - Reported inclination σ (`uncertainty`, one standard deviation): P's, or, where it is
//!   larger, the evidence of the innovations, `|ν̄|/g` with ν̄ the running mean (time
//!   constant 1 s) of the gravity innovation rotated into the earth frame. P alone was
//!   overconfident after accepted input no sensor reports (an attitude set 120° off by
//!   the host, a spin read through a clipped gyroscope, glitches): the error lay within
//!   2σ on 32-95 % of 60 s of still samples (tests/recovery.rs), because the filter
//!   only learns of such an error through the accelerometer, whose colour-scaled,
//!   adaptive variance makes it converge over seconds to tens of seconds while P shrinks
//!   on every sample. A consistent filter's innovations are white with zero mean; a
//!   persistent mean is the part of the error P does not know about, and at rest its
//!   length is the chord `2g sin(e/2)` of the inclination error e itself. Measured
//!   against the alternatives: (a) inflating P_qq on a gravity innovation gross for
//!   several samples in motion changes the estimate (BROAD must stay bit-identical) and
//!   needs a persistence rule that never fires on linear acceleration; (b) the classical
//!   consistency scaling, σ times √(mean NIS / 3) (NIS against `tr(H P Hᵀ) + 3r`, as the
//!   gross test), still left 61 of the 84 runs below 95 % (worst 48 %): at a large error
//!   the NIS grows as e² but the scale only as e, and P's σ is small; adding the
//!   innovation's power beyond `tr(H P Hᵀ) + 3r` to P's variance instead (covariance
//!   matching) left one run at 93.6 % and a host-set attitude with the zero-rate update
//!   at 86.5 %: the motion allowance (`accel_motion`) in r hides inclination errors below
//!   about 5°, which the mean does not. This σ is an output only: the estimate is
//!   bit-identical. Every EKF configuration of the recovery property now covers at least
//!   97 % of its still samples. On BROAD's 14 trials inclination coverage stays at 100 %
//!   (trial 21, fast combined motion: from 46 % to 100 %); the median σ is unchanged where
//!   the accelerometer sees gravity alone and grows under sustained translation (trials
//!   15 and 30: 15.7° and 7.1° to 27.1° and 21.6°, RMS errors 9.7° and 5.3°), where the
//!   accelerometer cannot tell tilt from acceleration. It costs 58 instructions per
//!   update (callgrind, baseline ISA: IMU 4620 to 4678, MARG 5274 to 5332).

use crate::filters::kinds::rest::{lp_gain, RestDetector, RestThresholds};
use crate::filters::params::settings;
use crate::filters::pipeline::estimator::Step;
use crate::math::lanes::Lanes;
use crate::math::{cos_and_sinc, cos_minus_sinc_over_x2, one_minus_exp_neg};
use crate::math::{Quat, Vec3};
use nalgebra::{Matrix3, Matrix3x4, Matrix4, Matrix4x3, SMatrix, Vector3};
use wide::f64x4;

settings! {
    /// The EKF's settings.
    pub struct EkfSettings {
        tau_omega: f64 = EKF_TAU_OMEGA 40 {
            unit: "s",
            default: 0.2,
            min: 1e-4,
            max: 1e6,
            zero_off: false,
            doc: "Correlation time of the angular-rate Markov process, eq. (9) (stable -1/tau form); \
                 default 0.2 (orient: the paper sets it from the motion's bandwidth without a \
                 value; a few Hz for hand and body motion).",
        },
        omega_std: f64 = EKF_OMEGA_STD 41 {
            unit: "rad/s",
            default: 3.0,
            min: 1e-3,
            max: 1e3,
            zero_off: false,
            doc: "Stationary standard deviation of the angular rate ('limit of the magnitude of the \
                 motion', section III.A); default 3 (orient: the paper gives no value; about 170 deg/s, \
                 the scale of hand and body rotation).",
        },
        tau_drift: f64 = EKF_TAU_DRIFT 42 {
            unit: "s",
            default: 100.0,
            min: 1e-3,
            max: 1e9,
            zero_off: false,
            doc: "Correlation time of the gyro drift Markov process, eq. (10) (stable -1/tau form); \
                 default 100 (orient: the paper gives no value; MEMS drift changes over minutes).",
        },
        drift_std: f64 = EKF_DRIFT_STD 43 {
            unit: "rad/s",
            default: 0.02,
            min: 1e-6,
            max: 10.0,
            zero_off: false,
            doc: "Stationary standard deviation of the gyro drift; default 0.02 (orient: the paper \
                 gives no value; about 1 deg/s covers consumer MEMS gyroscopes' typical zero-rate \
                 offset, 0.5 deg/s in the BMI270 and LSM6DSO datasheets).",
        },
        gyro_noise: f64 = EKF_GYRO_NOISE 44 {
            unit: "rad/s/sqrt(Hz)",
            default: 8.726_646_259_971_648e-4,
            min: 1e-5,
            max: 10.0,
            zero_off: false,
            doc: "Gyroscope noise density; default 0.05 deg/s/sqrt(Hz) (paper, section IV).",
        },
        accel_noise: f64 = EKF_ACCEL_NOISE 45 {
            unit: "m/s^2/sqrt(Hz)",
            default: 32e-6 * 9.80665,
            min: 1e-5,
            max: 100.0,
            zero_off: false,
            doc: "Accelerometer noise density; default 32 ug/sqrt(Hz) (paper, section IV).",
        },
        accel_motion: f64 = EKF_ACCEL_MOTION 46 {
            unit: "m/s^2",
            default: 0.5,
            min: 0.0,
            max: 1e3,
            zero_off: false,
            doc: "Standing allowance for linear acceleration added to the accelerometer noise \
                 (plus (|f|-g)^2 per sample); default 0.5 (orient: the paper's model has none and \
                 tolerates 'a modicum'; real recordings need it, BROAD trial 15).",
        },
        heading_std: f64 = EKF_HEADING_STD 47 {
            unit: "rad",
            default: 0.1,
            min: 1e-4,
            max: 10.0,
            zero_off: false,
            doc: "Standard deviation of the magnetometer heading measurement (the paper's proposed \
                 extension); default 0.1 (orient: about 6 deg \
                 for a clean field; heading_tau and heading_adapt_tau raise it when it is not).",
        },
        motion_tau: f64 = EKF_MOTION_TAU 48 {
            unit: "s",
            default: 0.5,
            min: 0.0,
            max: 100.0,
            zero_off: false,
            doc: "Correlation time of linear acceleration: its variance is counted once per \
                 2*motion_tau/dt samples (coloured, not white, noise); default 0.5 (orient: the \
                 length of a hand movement); 0 treats it as white, as the paper does.",
        },
        heading_tau: f64 = EKF_HEADING_TAU 49 {
            unit: "s",
            default: 1.0,
            min: 0.0,
            max: 1000.0,
            zero_off: false,
            doc: "Correlation time of magnetic heading errors: the heading variance is counted once \
                 per 2*heading_tau/dt samples; default 1 (orient: disturbances change as the sensor \
                 moves through a room's field); 0 treats them as white.",
        },
        rest_rate_std: f64 = EKF_REST_RATE_STD 50 {
            unit: "rad/s",
            default: 0.0,
            min: 1e-6,
            max: 10.0,
            zero_off: true,
            doc: "orient option: at detected rest (2 deg/s, 0.5 m/s^2, 0.5 deg tilt for 1.5 s) add \
                 the pseudo-measurement omega = 0 with this standard deviation (zero-rate update), \
                 which pins the drift delta to the resting gyro; default 0 = off (the paper).",
        },
        accel_adapt_tau: f64 = EKF_ACCEL_ADAPT_TAU 51 {
            unit: "s",
            default: 2.0,
            min: 1e-3,
            max: 1000.0,
            zero_off: true,
            doc: "Time constant of the accelerometer innovation's running power; the measurement \
                 variance is at least that power (colour-scaled), so sustained linear acceleration \
                 is trusted less (innovation-based adaptive noise, where the paper only allows 'a \
                 modicum'); default 2 (BROAD mean 9D within 0.15 deg over 1-5 s); 0 = off.",
        },
        heading_adapt_tau: f64 = EKF_HEADING_ADAPT_TAU 52 {
            unit: "s",
            default: 2.0,
            min: 1e-3,
            max: 1000.0,
            zero_off: true,
            doc: "Time constant of the heading innovation's running power, which likewise bounds \
                 the heading variance from below, so a disturbed field is trusted less; default 2 \
                 (orient: as accel_adapt_tau; BROAD trial 32 goes from 25.3 to 2.8 deg); 0 = off.",
        },
    }
    shared { gravity: f64 = GRAVITY }
}

mod blocks;
mod gross;
mod model;
use blocks::*;
use gross::*;
use model::*;
pub use model::{exp_and_jacobian, gravity_model};

/// How many stationary standard deviations of the drift process (10) a drift may reach
/// and still be one: 5 (a Gauss-Markov process leaves that band with probability 6e-7).
pub const DRIFT_PLAUSIBLE: f64 = 5.0;

/// The EKF. State in the native North-East-Down frame.
#[derive(Clone, Debug, PartialEq)]
pub struct Ekf {
    pub settings: EkfSettings,
    x: Blocks,
    p: Cov,
    rest: RestDetector,
    adapt: f64,
    adapt_h: f64,
    /// The running mean of the gravity innovation in the earth frame (m/s²), for the
    /// reported inclination σ only ([`Ekf::attitude_sigmas`]).
    nu_mean: Vec3,
}

impl Ekf {
    pub fn new(settings: EkfSettings) -> Ekf {
        crate::isa::prepare();
        let mut f = Ekf {
            settings,
            x: Blocks { q: vector_of((), Quat::IDENTITY), w: f64x4::splat(0.0), d: f64x4::splat(0.0) },
            p: Cov::diagonal(0.0, 0.0, 0.0),
            rest: RestDetector::default(),
            adapt: 0.0,
            adapt_h: 0.0,
            nu_mean: Vec3::ZERO,
        };
        f.reset_covariance();
        f
    }

    fn reset_covariance(&mut self) {
        let s = &self.settings;
        // q: about 10° of uncertainty (δq ≈ θ/2).
        self.p = Cov::diagonal(0.0076, s.omega_std * s.omega_std, s.drift_std * s.drift_std);
    }

    pub fn quaternion(&self) -> Quat {
        quat_of(self.x.q)
    }

    /// Sets the orientation (native NED), keeping the covariance.
    pub fn set_quaternion(&mut self, q: Quat) {
        self.x.q = vector_of((), q);
    }

    /// After a gap: the re-acquired orientation, ω from this gyroscope reading less the
    /// drift estimate δ (kept, but for the rest watch's still reading, which becomes it),
    /// the covariance back to its initial value (the orientation
    /// is as uncertain as at start-up), rest detection and adaptation started over.
    pub(crate) fn reacquire(&mut self, r: &crate::filters::pipeline::estimator::Reacquisition) -> bool {
        let (q, used_mag) = r.plain();
        if let Some(g) = r.still {
            // The rest watch's still reading is the drift δ (and ω is then zero), within
            // the band the drift process can produce (`configure`'s).
            let bound = DRIFT_PLAUSIBLE * self.settings.drift_std;
            let c = |x: f64| x.clamp(-bound, bound);
            self.x.d = f64x4::new([c(g.x), c(g.y), c(g.z), 0.0]);
        }
        let omega = r.gyro - self.drift();
        self.x.q = vector_of((), q);
        self.x.w = f64x4::new([omega.x, omega.y, omega.z, 0.0]);
        self.reset_covariance();
        self.rest = RestDetector::default();
        self.adapt = 0.0;
        self.adapt_h = 0.0;
        self.nu_mean = Vec3::ZERO;
        used_mag
    }

    /// Values an update could leave (see `filters::holds`): a unit q, bounded ω and δ,
    /// and a covariance that is a covariance: symmetric, positive semi-definite (a
    /// Cholesky factorisation of P + 1e-9·max(diag P)·I succeeds).
    pub(crate) fn valid(&self) -> bool {
        use crate::filters::state::holds;
        let mut p = self.p.clone();
        let mut m = [[0.0; 10]; 10];
        for (r, row) in m.iter_mut().enumerate() {
            for (c, v) in row.iter_mut().enumerate() {
                *v = *p.entry_mut(r, c);
            }
        }
        holds::unit(self.quaternion())
            && holds::rate(self.rate())
            && holds::rate(self.drift())
            && covariance(&m)
            && self.rest.valid()
            && self.adapt >= 0.0
            && self.adapt_h >= 0.0
            && holds::accel(self.nu_mean)
    }

    /// Visits the state as ten values [q, ω, δ], then P as a full 10×10 matrix in
    /// column-major order (the snapshot layout of format version 1).
    pub(crate) fn codec(&mut self, c: &mut dyn crate::filters::state::Codec) {
        for v in self.x.values_mut() {
            c.f64(v);
        }
        for col in 0..10 {
            for row in 0..10 {
                c.f64(self.p.entry_mut(row, col));
            }
        }
        self.rest.codec(c);
        c.f64(&mut self.adapt);
        c.f64(&mut self.adapt_h);
        c.f64(&mut self.nu_mean.x);
        c.f64(&mut self.nu_mean.y);
        c.f64(&mut self.nu_mean.z);
    }

    /// True when the last sample counted as rest (only tracked with `rest_rate_std` set).
    pub fn at_rest(&self) -> bool {
        self.rest.at_rest()
    }

    /// The angular rate estimate ω (rad/s).
    pub fn rate(&self) -> Vec3 {
        Vec3::new(lane(self.x.w, 0), lane(self.x.w, 1), lane(self.x.w, 2))
    }

    /// The gyro drift estimate δ (rad/s).
    /// Takes new settings, the state kept but for the drift δ, which is held to what the
    /// new drift process (10) allows: each axis within [`DRIFT_PLAUSIBLE`] stationary
    /// standard deviations (`drift_std`). A drift learned under a wider process (a
    /// larger `drift_std`, or a shorter `tau_drift` that let it follow rate errors)
    /// would otherwise keep the estimate turning while the gyroscope reads zero, for as
    /// long as the new, slower process takes to forget it (minutes at the defaults).
    /// An axis whose drift the new process cannot produce (|δ_i| beyond the band) starts
    /// over from the process's prior, zero with the stationary variance `drift_std`²; one
    /// whose variance is above that keeps its drift with that variance. Either is made
    /// independent of the other states (as [`reinit_rate`] does for ω), so that a
    /// gyroscope reading is not split between ω and a drift the process says cannot move.
    pub(crate) fn configure(&mut self, settings: EkfSettings) {
        self.settings = settings;
        let var = settings.drift_std * settings.drift_std;
        let bound = DRIFT_PLAUSIBLE * settings.drift_std;
        for i in 0..3 {
            let d = self.x.d.as_array_ref()[i];
            if d.abs() > bound {
                // No drift of this process: its prior, zero.
                reinit_drift(&mut self.x, &mut self.p, i, 0.0, var);
            } else if self.p.dd[i].as_array_ref()[i] > var {
                reinit_drift(&mut self.x, &mut self.p, i, d, var);
            }
        }
    }

    pub fn drift(&self) -> Vec3 {
        Vec3::new(lane(self.x.d, 0), lane(self.x.d, 1), lane(self.x.d, 2))
    }

    /// One standard deviation (rad) of the heading and inclination errors, from the q
    /// block of P: the earth-frame error angle of an error Δq is δθ = 2 vec(Δq ⊗ q̂*),
    /// linear in Δq; its row for the earth axis e is J_e = 2 (ê ⊗ q̂) (the heading row is
    /// the `hq` of the magnetometer update), so var(δθ_e) = J_e P_qq J_eᵀ. Heading is
    /// about the vertical (z in NED), inclination the root of the two horizontal ones, or,
    /// where larger, `|ν̄|/g`, the persistent gravity innovation (module documentation).
    pub fn attitude_sigmas(&self) -> (f64, f64) {
        let q = self.quaternion();
        let var = |e: Quat| -> f64 {
            let j = vector_of::<f64x4>((), e * q) * f64x4::splat(2.0);
            dot4(j, self.p.times_q(j).q).max(0.0)
        };
        let (x, y, z) =
            (Quat::new(0.0, 1.0, 0.0, 0.0), Quat::new(0.0, 0.0, 1.0, 0.0), Quat::new(0.0, 0.0, 0.0, 1.0));
        let g2 = self.settings.gravity * self.settings.gravity;
        (var(z).sqrt(), (var(x) + var(y)).max(self.nu_mean.norm_squared() / g2).sqrt())
    }

    /// The diagonal of the state covariance P, in state order [q0..q3, ω, δ].
    pub fn covariance_diagonal(&self) -> [f64; 10] {
        let p = &self.p;
        let mut d = [0.0; 10];
        for (i, v) in d.iter_mut().enumerate() {
            *v = match i {
                0..=3 => lane(p.qq[i], i),
                4..=6 => lane(p.ww[i - 4], i - 4),
                _ => lane(p.dd[i - 7], i - 7),
            };
        }
        d
    }

    /// One step; `None`, with nothing changed, when it would not be finite. Runs with
    /// 256-bit lanes where the CPU has AVX (`crate::isa::widest_lanes`; the same bits).
    ///
    /// A step that fails from a covariance which has lost its conditioning (settings
    /// changed under a running filter to extreme values, say) would fail again on every
    /// later sample. So it is tried once more from a fresh start of the uncertain parts:
    /// P at its initial value and ω at this gyroscope reading less the drift estimate,
    /// the orientation and drift kept. Only if that fails too is the step refused.
    #[inline(always)]
    pub fn update(&mut self, dt: f64, gyro: Vec3, accel: Option<Vec3>, mag: Option<Vec3>) -> Option<Step> {
        match self.step(dt, gyro, accel, mag, true) {
            Ok(step) => Some(step),
            Err(Stop::Refused) => self.retry_from_fresh_covariance(dt, gyro, accel, mag),
            Err(Stop::RateJump(jumped)) => self.update_after_jump(dt, gyro, accel, mag, jumped),
        }
    }

    /// [`Ekf::update`] after ω was re-initialised on the axes whose gyroscope reading
    /// failed the NIS test; nothing changed when the step is refused.
    #[cold]
    #[inline(never)]
    fn update_after_jump(
        &mut self,
        dt: f64,
        gyro: Vec3,
        accel: Option<Vec3>,
        mag: Option<Vec3>,
        jumped: [bool; 3],
    ) -> Option<Step> {
        let before = self.clone();
        let s = &self.settings;
        let a_w = 1.0 - one_minus_exp_neg(dt / s.tau_omega);
        let a_d = 1.0 - one_minus_exp_neg(dt / s.tau_drift);
        let rg = s.gyro_noise * s.gyro_noise / (2.0 * dt);
        reinit_rate(&mut self.x, &mut self.p, gyro, jumped, rg / (a_w * a_w), (a_w, a_d));
        let step = match self.step(dt, gyro, accel, mag, false) {
            Ok(step) => Some(step),
            Err(_) => self.retry_from_fresh_covariance(dt, gyro, accel, mag),
        };
        if step.is_none() {
            *self = before;
        }
        step
    }

    #[cold]
    #[inline(never)]
    fn retry_from_fresh_covariance(
        &mut self,
        dt: f64,
        gyro: Vec3,
        accel: Option<Vec3>,
        mag: Option<Vec3>,
    ) -> Option<Step> {
        let before = self.clone();
        let omega = gyro - self.drift();
        self.x.w = f64x4::new([omega.x, omega.y, omega.z, 0.0]);
        self.reset_covariance();
        let step = self.step(dt, gyro, accel, mag, false).ok();
        if step.is_none() {
            *self = before;
        }
        step
    }

    /// The step itself, in the widest lanes the CPU has. Not inlined into the retry
    /// above: one copy of the (large) step serves both calls.
    #[inline(never)]
    fn step(
        &mut self,
        dt: f64,
        gyro: Vec3,
        accel: Option<Vec3>,
        mag: Option<Vec3>,
        test_rate: bool,
    ) -> Result<Step, Stop> {
        struct Run<'a> {
            ekf: &'a mut Ekf,
            dt: f64,
            gyro: Vec3,
            accel: Option<Vec3>,
            mag: Option<Vec3>,
            test_rate: bool,
        }
        impl crate::isa::WithLanes for Run<'_> {
            type Out = Result<Step, Stop>;
            #[inline(always)]
            fn run<V: Lanes>(self, t: V::Token) -> Result<Step, Stop> {
                self.ekf.update_in::<V>(t, self.dt, self.gyro, self.accel, self.mag, self.test_rate)
            }
        }
        crate::isa::widest_lanes(Run { ekf: self, dt, gyro, accel, mag, test_rate })
    }

    /// [`Ekf::update`] with lane type `V`; with `test_rate`, first the gyroscope rows'
    /// NIS test (12) ([`rate_jumps`]), on the prediction's own factors and state.
    #[inline(always)]
    fn update_in<V: Lanes>(
        &mut self,
        tk: V::Token,
        dt: f64,
        gyro: Vec3,
        accel: Option<Vec3>,
        mag: Option<Vec3>,
        test_rate: bool,
    ) -> Result<Step, Stop> {
        let s = &self.settings;
        let mut step = Step::default();

        // ---- predict, eqs. (8)-(10), discretised ----
        // ω_k is the rate over the interval ending at sample k (what a gyroscope sample
        // reports): ω⁺ = a_ω ω + w, then q⁺ = q ⊗ exp(ω⁺ dt/2). The rate's process noise
        // w thus reaches q through the same exponential map, and this sample's gyroscope
        // reading corrects q in this update rather than one sample late.
        //
        // With F = [[R(e), a_ω D, 0], [0, a_ω I, 0], [0, 0, a_δ I]] (D = ∂q⁺/∂ω⁺) and
        // G = [D; I; 0], P⁺ = F P Fᵀ + G Q_ω Gᵀ + Q_δ works out per block as
        //   T = R P_qq + a_ω D P_ωq,  B = R P_qω + a_ω D P_ωω,
        //   P⁺_qω = a_ω B + q_ω D,    P⁺_qq = T Rᵀ + P⁺_qω Dᵀ,
        //   P⁺_qδ = a_δ (R P_qδ + a_ω D P_ωδ),
        //   P⁺_ωω = a_ω² P_ωω + q_ω I,  P⁺_ωδ = a_ω a_δ P_ωδ,  P⁺_δδ = a_δ² P_δδ + q_δ I.
        // a = e^{−dt/τ} as 1 − c with c = 1 − e^{−dt/τ} (`one_minus_exp_neg`: a series for
        // dt/τ under 1/8, libm's expm1 beyond), and the Markov processes' variance
        // factor 1 − a² as c (2 − c), which does not cancel when dt ≪ τ (the drift's
        // τ = 100 s: 1 − a² ≈ 7e-5 at 286 Hz, where 1 − a·a kept four digits fewer).
        let c_w = one_minus_exp_neg(dt / s.tau_omega);
        let c_d = one_minus_exp_neg(dt / s.tau_drift);
        let (a_w, a_d) = (1.0 - c_w, 1.0 - c_d);
        let q = quat_of(self.x.q);
        let x0 = Blocks::<V>::load(&self.x, tk);
        let mut x = Blocks { q: x0.q, w: x0.w * V::splat(tk, a_w), d: x0.d * V::splat(tk, a_d) };
        let qw = s.omega_std * s.omega_std * (c_w * (2.0 - c_w));
        let qd = s.drift_std * s.drift_std * (c_d * (2.0 - c_d));
        let rg = s.gyro_noise * s.gyro_noise / (2.0 * dt);
        if test_rate {
            // The gyroscope rows' NIS test (12) against the predicted reading ω⁺ + δ⁺
            // (the products a_ω ω_i + a_δ δ_i), with its cheap bound first ([`rate_jumps`]).
            let (w, d) = (x.w.to_array(), x.d.to_array());
            let g = [gyro.x, gyro.y, gyro.z];
            let nu2: [f64; 3] = array(
                #[inline(always)]
                |i| {
                    let nu = g[i] - (w[i] + d[i]);
                    nu * nu
                },
            );
            let var = (qw + qd) + rg;
            let bound = GROSS_NIS * var;
            if (nu2[0] > bound) | (nu2[1] > bound) | (nu2[2] > bound) {
                let jumped = rate_jumps(&self.p, nu2, (a_w, a_d), var);
                if jumped != [false; 3] {
                    return Err(Stop::RateJump(jumped));
                }
            }
        }
        // D = ∂q⁺/∂ω⁺ (4×3)
        let (e, dq_dw) = exp_and_d::<V>(tk, q, Vec3::new(lane(x.w, 0), lane(x.w, 1), lane(x.w, 2)), 0.5 * dt);
        x.q = vector_of(tk, q * e);
        let r = right(e);
        let rc = cols(tk, &r);
        let a = dq_dw.map(|c| c * V::splat(tk, a_w)); // a_ω D
                                                      // P as stored, read in place: entries as arrays, columns loaded where used.
        let p0 = &self.p;
        let (qq0, qw0, qd0) = (in_place(&p0.qq), in_place(&p0.qw), in_place(&p0.qd));
        let (ww0, wd0) = (in_place(&p0.ww), in_place(&p0.wd));
        // (A B)(k, j) reads B's column j, row k; (A Bᵀ) reads B's column k, row j.
        let t: Cols<4, V> = add_cols(mul_cols(&rc, |k, j| qq0[j][k]), mul_cols(&a, |k, j| qw0[k][j]));
        let b: Cols<3, V> = add_cols(mul_cols(&rc, |k, j| qw0[j][k]), mul_cols(&a, |k, j| ww0[j][k]));
        let p_qw: Cols<3, V> = array(
            #[inline(always)]
            |j| b[j] * V::splat(tk, a_w) + dq_dw[j] * V::splat(tk, qw),
        );
        let d_e = entries(&dq_dw);
        let p_qq: Cols<4, V> = add_cols(mul_cols(&t, |k, j| r[(j, k)]), mul_cols(&p_qw, |k, j| d_e[k][j]));
        let p_qd: Cols<3, V> = add_cols(mul_cols(&rc, |k, j| qd0[j][k]), mul_cols(&a, |k, j| wd0[j][k]));
        let pq = entries(&p_qq);
        let half = V::splat(tk, 0.5);
        let (aww, awd, add) = (V::splat(tk, a_w * a_w), V::splat(tk, a_w * a_d), V::splat(tk, a_d * a_d));
        let mut p = Cov {
            // (P + Pᵀ)/2: column j plus row j.
            qq: array(
                #[inline(always)]
                |j| (p_qq[j] + V::new(tk, [pq[0][j], pq[1][j], pq[2][j], pq[3][j]])) * half,
            ),
            qw: p_qw,
            qd: p_qd.map(|c| c * V::splat(tk, a_d)),
            ww: array(
                #[inline(always)]
                |j| V::load(tk, p0.ww[j]) * aww + unit(tk, j, qw),
            ),
            wd: array(
                #[inline(always)]
                |j| V::load(tk, p0.wd[j]) * awd,
            ),
            dd: array(
                #[inline(always)]
                |j| V::load(tk, p0.dd[j]) * add + unit(tk, j, qd),
            ),
        };

        // ---- update with z = [f, ω_IMU], eqs. (11)-(13) ----
        // R is diagonal, so the accelerometer's rows and then the gyroscope's are
        // absorbed as two batches of three (the same posterior as one batch of six: the
        // gyroscope rows are linear, so their innovation at the updated state is the
        // batch's less h·(x − x⁻)); one pass over P per batch instead of one per row.
        let mut adapt = self.adapt;
        let mut adapt_h = self.adapt_h;
        let mut nu_mean = None;
        // Rest (with `rest_rate_std` set) depends on the readings only, so it is decided
        // first: it also tells the accelerometer update that f is gravity alone.
        let mut rest = None;
        let mut at_rest = false;
        if s.rest_rate_std > 0.0 {
            let mut detector = self.rest.clone();
            at_rest = detector.update(dt, gyro, accel, &RestThresholds::DEFAULT);
            rest = Some(detector);
        }
        if let Some(acc) = accel {
            step.used_accel = true;
            let q_pred = x.q;
            let (fh, hf) = gravity_model(quat_of(q_pred), s.gravity);
            // The direction of f at the length g: a norm different from g says nothing
            // about the attitude, and left in, it would pull on the quaternion's norm.
            let dev = acc.norm() - s.gravity;
            let nu = acc * (s.gravity / acc.norm()) - fh;
            // Linear acceleration is low-frequency, not white: over its correlation time
            // motion_tau it biases 2·motion_tau/dt samples alike, so its per-sample
            // variance is scaled by that count (the white-noise equivalent of a
            // first-order Markov process's low-frequency power).
            let colour = (2.0 * s.motion_tau / dt).max(1.0);
            let white = s.accel_noise * s.accel_noise / (2.0 * dt);
            let motion = s.accel_motion * s.accel_motion + dev * dev;
            let ra0 = white + motion * colour;
            let h: [V; 3] = array(
                #[inline(always)]
                |i| V::new(tk, [hf[(i, 0)], hf[(i, 1)], hf[(i, 2)], hf[(i, 3)]]),
            );
            let mut u = h.map(|hq| p.times_q(hq));
            let nu2 = nu.norm_squared();
            // The reported inclination σ's evidence (output only).
            let mean = self.nu_mean;
            nu_mean = Some(mean + (quat_of(q_pred).rotate(nu) - mean) * lp_gain(dt, EXCESS_TAU));
            let mut ra = ra0;
            if at_rest {
                // At rest (the zero-rate update's detector) f is gravity alone: the NIS
                // test (see the module documentation), the innovation's power against the
                // power the model predicts for it, tr(H P Hᵀ) plus three axes of noise and
                // linear acceleration counted as a variance (not colour-scaled). A gross
                // innovation is the attitude's error; neither it nor any other at rest is
                // linear acceleration, so none feeds or takes the adaptive floor.
                let hph = (dot4(h[0], u[0].q) + dot4(h[1], u[1].q)) + dot4(h[2], u[2].q);
                let expected = hph + 3.0 * (white + motion);
                if nu2 > GROSS_NIS * expected {
                    inflate_attitude(&mut p, x.q, (nu2 - expected) / (2.0 * s.gravity * s.gravity));
                    u = h.map(|hq| p.times_q(hq));
                }
            } else if s.accel_adapt_tau > 0.0 {
                // The innovation's recent power per axis: linear acceleration the standing
                // allowance does not cover (sustained translation) shows up there first.
                adapt += (nu2 / 3.0 - adapt) * lp_gain(dt, s.accel_adapt_tau);
                ra = ra.max(adapt * colour);
            }
            let s3 = array(
                #[inline(always)]
                |i| {
                    array(
                        #[inline(always)]
                        |j| dot4(h[i], u[j].q) + if i == j { ra } else { 0.0 },
                    )
                },
            );
            absorb3(&mut x, &mut p, &u, s3, [nu.x, nu.y, nu.z]).ok_or(Stop::Refused)?;
        }
        // Gyroscope rows: ω_IMU,i = ω_i + δ_i, linear.
        let u: [Blocks<V>; 3] = array(
            #[inline(always)]
            |j| p.column_w(j).plus(&p.column_d(j)),
        );
        let s3 = array(
            #[inline(always)]
            |i| {
                array(
                    #[inline(always)]
                    |j| lane(u[j].w, i) + lane(u[j].d, i) + if i == j { rg } else { 0.0 },
                )
            },
        );
        let nu_g = [gyro.x, gyro.y, gyro.z];
        let innovation = array(
            #[inline(always)]
            |i| nu_g[i] - (lane(x.w, i) + lane(x.d, i)),
        );
        absorb3(&mut x, &mut p, &u, s3, innovation).ok_or(Stop::Refused)?;
        if at_rest {
            // At rest the rate is zero: the pseudo-measurement ω = 0.
            let rz = s.rest_rate_std * s.rest_rate_std;
            let u: [Blocks<V>; 3] = array(
                #[inline(always)]
                |j| p.column_w(j),
            );
            let s3 = array(
                #[inline(always)]
                |i| {
                    array(
                        #[inline(always)]
                        |j| lane(u[j].w, i) + if i == j { rz } else { 0.0 },
                    )
                },
            );
            let innovation = array(
                #[inline(always)]
                |i| -lane(x.w, i),
            );
            absorb3(&mut x, &mut p, &u, s3, innovation).ok_or(Stop::Refused)?;
        }
        let q_norm = dot4(x.q, x.q).sqrt();
        // An absurd reading can blow the correction up: refuse the step rather than
        // divide by an overflowed (or vanished) norm.
        if !(q_norm.is_finite() && q_norm > 1e-3) {
            return Err(Stop::Refused);
        }
        x.q /= V::splat(tk, q_norm);

        // ---- heading from the magnetometer (moves heading only) ----
        if let (Some(m), true) = (mag, step.used_accel) {
            let q = quat_of(x.q);
            let me = q.rotate(m);
            let horizontal = (me.x * me.x + me.y * me.y).sqrt();
            if horizontal > 1e-6 * m.norm() {
                step.used_mag = true;
                let innovation = -crate::math::atan2(me.y, me.x);
                // Direction of a heading change in q: ∂q/∂ψ = ½ ẑ ⊗ q.
                // ½ ẑ ⊗ q multiplied out: the product's other terms are zeros.
                let dq: V = V::new(tk, [-(0.5 * q.z), -(0.5 * q.y), 0.5 * q.x, 0.5 * q.w]);
                let hq = dq * V::splat(tk, 4.0);
                let v = p.times_q(hq);
                let p_psi = dot4(hq, v.q);
                // Magnetic disturbances are low-frequency too: count the heading variance
                // once per 2·heading_tau/dt samples, like linear acceleration.
                let colour_psi = (2.0 * s.heading_tau / dt).max(1.0);
                let mut r_psi = s.heading_std * s.heading_std * colour_psi;
                if s.heading_adapt_tau > 0.0 {
                    // Likewise for heading: a magnetic disturbance raises the innovation's
                    // recent power, and with it the variance, so the field is trusted less.
                    adapt_h += (innovation * innovation - adapt_h) * lp_gain(dt, s.heading_adapt_tau);
                    r_psi = r_psi.max(adapt_h * colour_psi);
                }
                let k_psi = p_psi / (p_psi + r_psi);
                let (c, s) = crate::math::cos_sin(0.5 * (k_psi * innovation));
                // exp(k_ψ ν ẑ/2) ⊗ q = (c, 0, 0, s) ⊗ q multiplied out (the other terms are
                // zeros).
                x.q =
                    V::new(tk, [c * q.w - s * q.z, c * q.x - s * q.y, c * q.y + s * q.x, c * q.z + s * q.w]);
                // The gain k = [dq k_ψ; 0; 0] is restricted, not optimal, so the full
                // Joseph form applies: with v = P hᵀ,
                // P ← P − k vᵀ − v kᵀ + (h v + r) k kᵀ, which touches the q rows only.
                let k: V = dq * V::splat(tk, k_psi);
                let (ke, ve) = (k.to_array(), v.q.to_array());
                let s_psi = V::splat(tk, p_psi + r_psi);
                for j in 0..4 {
                    let (kj, vj) = (V::splat(tk, ke[j]), V::splat(tk, ve[j]));
                    p.qq[j] = p.qq[j] - (k * vj + v.q * kj) + (k * kj) * s_psi;
                }
                sub_outer(&mut p.qw, k, v.w);
                sub_outer(&mut p.qd, k, v.d);
            }
        }
        if !(x.is_finite() && p.is_finite()) {
            return Err(Stop::Refused);
        }
        self.x = x.store();
        p.store_into(&mut self.p);
        self.adapt = adapt;
        self.adapt_h = adapt_h;
        if let Some(m) = nu_mean {
            self.nu_mean = m;
        }
        if let Some(r) = rest {
            self.rest = r;
        }
        Ok(step)
    }
}

#[cfg(test)]
mod tests;

/// The common lifecycle's view of this kind (see [`crate::filters::pipeline::estimator::Estimator`]).
mod estimator_impl {
    use super::*;
    use crate::filters::pipeline::estimator::estimator;
    use crate::filters::Diagnostics;

    estimator!(impl for Ekf { settings: EkfSettings, native: Ned, own_startup: false, diagnostics: GYRO_BIAS | REST | RATE | COVARIANCE } {
        #[inline(always)]
        fn update(&mut self, dt: f64, gyro: Vec3, accel: Option<Vec3>, mag: Option<Vec3>) -> Option<Step> {
            Ekf::update(self, dt, gyro, accel, mag)
        }

        fn configure(&mut self, settings: EkfSettings) {
            Ekf::configure(self, settings);
        }

        fn diagnose(&self, d: &mut Diagnostics) {
            d.gyro_bias = self.drift();
            d.rate = self.rate();
            d.covariance = self.covariance_diagonal();
            d.rest = if Ekf::at_rest(self) { 1.0 } else { 0.0 };
        }

        fn fields(&self) -> u32 {
            let all = crate::filters::Kind::Ekf.diagnostics();
            if self.settings.rest_rate_std > 0.0 {
                all
            } else {
                all & !crate::filters::diag::REST
            }
        }

        fn at_rest(&self) -> bool {
            self.settings.rest_rate_std > 0.0 && Ekf::at_rest(self)
        }

        fn learns_bias_in_motion(&self) -> bool {
            // The drift δ is part of the state the gravity measurement corrects (drift_std
            // is above zero by its range).
            true
        }

        fn uncertainty(&self) -> crate::filters::Uncertainty {
            let (heading, inclination) = self.attitude_sigmas();
            crate::filters::Uncertainty { heading: Some(heading), inclination: Some(inclination) }
        }
    });
}
