//! What a decoded snapshot may hold (see [`crate::Filter::load`]): the checks each kind's
//! `valid` is built from. The codec already refuses NaN and infinities.

use crate::filters::pipeline::sample::MAX_ACCEL;
use crate::filters::pipeline::sample::MAX_GYRO;
use crate::filters::pipeline::sample::MAX_MAG;
use crate::math::{Quat, Vec3};

/// A unit quaternion, as every update leaves one (normalised to rounding).
pub fn unit(q: Quat) -> bool {
    (q.norm_squared() - 1.0).abs() <= 1e-9
}

/// A product of three quaternions that [`unit`] accepts, not normalised again (the robust
/// kind's output): `|q|²` within `(1 ± 1e-9)³` of 1, with room for rounding.
pub fn unit_product_of_three(q: Quat) -> bool {
    (q.norm_squared() - 1.0).abs() <= 3.1e-9
}

/// Estimates follow the readings, and a blend of bounded readings and predictions
/// may overshoot them a little: a decoded estimate must stay within ten times the
/// readings' physical bound (a forged 1e300 is refused).
const MARGIN: f64 = 10.0;

/// A rate: a bias or a rate estimate.
pub fn rate(v: Vec3) -> bool {
    v.max_abs() < MARGIN * MAX_GYRO
}

/// The variance of a rate: at most the square of [`rate`]'s bound.
pub fn rate_variance(x: f64) -> bool {
    (0.0..=(MARGIN * MAX_GYRO) * (MARGIN * MAX_GYRO)).contains(&x)
}

/// An accelerometer-like value (a low-pass of readings, a reference).
pub fn accel(v: Vec3) -> bool {
    v.max_abs() < MARGIN * MAX_ACCEL
}

/// A magnetometer-like value.
pub fn mag(v: Vec3) -> bool {
    v.max_abs() < MARGIN * MAX_MAG
}

/// A reading's largest norm, √3 · bound, with room for the rounding of a rotated
/// reading's norm.
pub const MAG_NORM_MAX: f64 = 1.732_050_807_568_877_2 * MAX_MAG * (1.0 + 1e-12);

/// A mean of magnetometer norms: no more than [`MAG_NORM_MAX`].
pub fn mag_norm(x: f64) -> bool {
    (0.0..=MAG_NORM_MAX).contains(&x)
}

/// A squared deviation between magnetometer-like values.
pub fn mag_spread(x: f64) -> bool {
    (0.0..(2.0 * MARGIN * MAX_MAG).powi(2)).contains(&x)
}

/// A value in `[lo, hi]`.
pub fn within(x: f64, lo: f64, hi: f64) -> bool {
    (lo..=hi).contains(&x)
}
