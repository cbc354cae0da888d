//! Internal states a host may show, the same struct for every kind.

use crate::math::Vec3;

/// Bits of [`Diagnostics::present`] and [`Kind::diagnostics`](crate::Kind::diagnostics),
/// also the header's `ORIENT_DIAG_*` (rendered from this table, see `src/ffi/bits.rs`).
pub mod diag {
    crate::filters::flags::bits! {
        /// gyro_bias holds a value.
        GYRO_BIAS = 1;
        /// rest holds a value.
        REST = 2;
        /// alpha holds a value.
        ALPHA = 4;
        /// mu_ka holds a value.
        MU_KA = 8;
        /// mu_km holds a value.
        MU_KM = 16;
        /// mu_k holds a value.
        MU_K = 32;
        /// rate holds a value.
        RATE = 64;
        /// covariance holds values.
        COVARIANCE = 128;
    }
}

/// Internal states a host may show, the same struct for every kind. A field whose bit in
/// `present` is clear does not apply to this kind (or not yet) and holds NaN.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Diagnostics {
    /// [`diag`] bits of the fields that hold values.
    pub present: u32,
    /// Gyroscope bias being subtracted (rad/s): Mahony's b, McGinnis' ω_b, the EKF's drift
    /// δ, GMVDK's regression bias.
    pub gyro_bias: Vec3,
    /// The last sample counted as rest: 1.0, else 0.0 (McGinnis: gains active; the robust
    /// kind: its rest detector; the EKF, Madgwick and Mahony: with their rest options on).
    pub rest: f64,
    /// GMVDK accelerometer trust α of the last update.
    pub alpha: f64,
    /// GMVDK μ_KA, μ_KM and μ_K of the last update with a magnetometer.
    pub mu_ka: f64,
    pub mu_km: f64,
    pub mu_k: f64,
    /// EKF angular rate state ω (rad/s).
    pub rate: Vec3,
    /// EKF covariance diagonal, state order [q0, q1, q2, q3, ω, δ].
    pub covariance: [f64; 10],
}

/// One standard deviation of the orientation's error (rad), where a kind has a model of
/// it (see [`crate::Filter::uncertainty`]); `None` where it has none.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Uncertainty {
    /// The heading error, about the earth's vertical: the EKF's from its covariance P,
    /// the robust kind's from its heading error model (it grows while the magnetometer
    /// is distrusted or absent, and settles while it is used; see
    /// [`crate::Filter::uncertainty`]).
    pub heading: Option<f64>,
    /// The inclination error: the tilt of the estimated vertical, the root of the
    /// variances about the two horizontal axes (the EKF's, from P).
    pub inclination: Option<f64>,
}

impl Default for Diagnostics {
    fn default() -> Self {
        let nan = f64::NAN;
        Diagnostics {
            present: 0,
            gyro_bias: Vec3::new(nan, nan, nan),
            rest: nan,
            alpha: nan,
            mu_ka: nan,
            mu_km: nan,
            mu_k: nan,
            rate: Vec3::new(nan, nan, nan),
            covariance: [nan; 10],
        }
    }
}

impl Diagnostics {
    /// Sets every field whose bit in `present` is clear back to NaN, so that an absent
    /// field never holds a value a kind computed anyway.
    pub(crate) fn clear_absent(&mut self) {
        let absent = Diagnostics::default();
        let keep = |bit: u32| self.present & bit != 0;
        if !keep(diag::GYRO_BIAS) {
            self.gyro_bias = absent.gyro_bias;
        }
        if !keep(diag::REST) {
            self.rest = absent.rest;
        }
        if !keep(diag::ALPHA) {
            self.alpha = absent.alpha;
        }
        if !keep(diag::MU_KA) {
            self.mu_ka = absent.mu_ka;
        }
        if !keep(diag::MU_KM) {
            self.mu_km = absent.mu_km;
        }
        if !keep(diag::MU_K) {
            self.mu_k = absent.mu_k;
        }
        if !keep(diag::RATE) {
            self.rate = absent.rate;
        }
        if !keep(diag::COVARIANCE) {
            self.covariance = absent.covariance;
        }
    }
}
