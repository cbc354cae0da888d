//! Vectors, quaternions and earth frames.
//!
//! Conventions used everywhere in orient:
//! - quaternions are Hamilton (`i*j = k`), scalar first, fields named `w, x, y, z`;
//! - an orientation `q` rotates body (sensor) coordinates into earth coordinates:
//!   `v_earth = q ⊗ [0, v_body] ⊗ q*`, which is `v_earth = R(q) · v_body`;
//! - transcendental functions come from the `libm` crate so that results are
//!   bit-identical on every platform (std's `sqrt` is exact everywhere and is kept).

#![forbid(unsafe_code)]

pub(crate) mod frame;
pub(crate) mod lanes;
mod quat;
mod vec3;

pub use frame::Frame;
pub use quat::{Euler, Quat};
pub use vec3::Vec3;

/// `(cos x, sin x / x)` from `x²` alone, by their Taylor series to the 8th power:
/// `1 − x²/2! + x⁴/4! − x⁶/6! + x⁸/8!` and `1 − x²/3! + x⁴/5! − x⁶/7! + x⁸/9!`. For
/// `x² ≤ 1/256` the remainders are below 2.6e-19, under half an ulp of either value;
/// callers check that range (outside it, use `libm::sincos`). No root, no division and
/// no range reduction: for the small angles of one filter step it replaces a `sincos`
/// and the root and division that find `x` (their cost: docs/PERFORMANCE.md).
#[inline(always)]
pub fn cos_and_sinc(x2: f64) -> (f64, f64) {
    let c = 1.0 + x2 * (-1.0 / 2.0 + x2 * (1.0 / 24.0 + x2 * (-1.0 / 720.0 + x2 * (1.0 / 40320.0))));
    let sinc = 1.0 + x2 * (-1.0 / 6.0 + x2 * (1.0 / 120.0 + x2 * (-1.0 / 5040.0 + x2 * (1.0 / 362880.0))));
    (c, sinc)
}

/// `(cos x, sin x)`: by [`cos_and_sinc`] for `x² < 1/256` (the small turns of one filter
/// step: no range reduction), by `libm::sincos` beyond.
#[inline(always)]
pub fn cos_sin(x: f64) -> (f64, f64) {
    if x * x < 1.0 / 256.0 {
        let (c, sinc) = cos_and_sinc(x * x);
        (c, sinc * x)
    } else {
        let (s, c) = libm::sincos(x);
        (c, s)
    }
}

/// `atan2(y, x)`: by [`atan_over`] for `4|y| < x` (angles under atan(1/4), about 14°:
/// no quadrant tests, no range reduction), by `libm::atan2` elsewhere. The test is
/// strict, so `x > 0` there, where `atan2(y, x) = atan(y / x)`.
#[inline(always)]
pub fn atan2(y: f64, x: f64) -> f64 {
    if 4.0 * y.abs() < x {
        let t = y / x;
        return t * atan_over(t * t);
    }
    libm::atan2(y, x)
}

/// `(cos x − sin x / x) / x²` from `x²` alone, by its Taylor series to the 8th power:
/// `Σ_{k≥1} (−1)ᵏ 2k x²ᵏ⁻² / (2k + 1)!` = `−1/3 + x²/30 − x⁴/840 + x⁶/45360 − x⁸/3991680`.
/// For `x² ≤ 1/256` the first term left out, `x¹⁰/518918400`, is below 1.8e-21, under a
/// ten-thousandth of an ulp of the value (about −1/3); callers check that range. The
/// exponential map's Jacobian needs it beside [`cos_and_sinc`] (the EKF's predict).
#[inline(always)]
pub fn cos_minus_sinc_over_x2(x2: f64) -> f64 {
    -1.0 / 3.0 + x2 * (1.0 / 30.0 + x2 * (-1.0 / 840.0 + x2 * (1.0 / 45360.0 + x2 * (-1.0 / 3991680.0))))
}

/// `1 − e^{−x}`, the weight a first-order low-pass with time constant τ gives a new
/// sample over a step dt (`x = dt/τ`). For `0 ≤ x < 1/8` (every step shorter than τ/8)
/// by the series
/// `x − x²/2! + x³/3! − … + x¹¹/11!`: the first term left out is below 2⁻⁶¹ of the sum.
/// Elsewhere [`one_minus_exp_neg_libm`], the readable form the series is tested against.
/// dt jitters on every host, so a memo of the last dt rarely spares the call; the series
/// costs fewer instructions than `1 − libm::exp(−x)` (docs/PERFORMANCE.md), and it keeps
/// the bits that `1 − exp(−x)` loses to cancellation (that form's relative error grows
/// as 2⁻⁵³/x).
#[inline(always)]
pub fn one_minus_exp_neg(x: f64) -> f64 {
    if !(0.0..1.0 / 8.0).contains(&x) {
        return one_minus_exp_neg_libm(x);
    }
    // Horner's scheme from the x¹¹ term down: c₁₁, then c + x·(…) for c = c₁₀ … c₁.
    const C: [f64; 10] = [
        -1.0 / 3628800.0,
        1.0 / 362880.0,
        -1.0 / 40320.0,
        1.0 / 5040.0,
        -1.0 / 720.0,
        1.0 / 120.0,
        -1.0 / 24.0,
        1.0 / 6.0,
        -1.0 / 2.0,
        1.0,
    ];
    x * C.iter().fold(1.0 / 39916800.0, |p, c| c + x * p)
}

/// `1 − e^{−x}` as libm's `−expm1(−x)` (correct to about an ulp for every x).
#[cold]
#[inline(never)]
pub fn one_minus_exp_neg_libm(x: f64) -> f64 {
    -libm::expm1(-x)
}

/// `asin(s) / s` from `s²` alone, by its Taylor series `Σ C(2k, k) s²ᵏ / (4ᵏ (2k + 1))`
/// to the 14th power. For `s² ≤ 1/256` the remainder is below 6.3e-22; callers check
/// that range.
#[inline(always)]
pub fn asin_over(s2: f64) -> f64 {
    1.0 + s2
        * (1.0 / 6.0
            + s2 * (3.0 / 40.0
                + s2 * (5.0 / 112.0
                    + s2 * (35.0 / 1152.0
                        + s2 * (63.0 / 2816.0 + s2 * (231.0 / 13312.0 + s2 * (143.0 / 10240.0)))))))
}

/// `atan(t) / t` from `t²` alone, by its Taylor series `Σ (−1)ᵏ t²ᵏ / (2k + 1)` to the
/// 24th power. For `t² ≤ 1/16` the first term left out, `t²⁶/27`, is below 8.3e-18, under
/// a tenth of an ulp; callers check that range (outside it, use `libm::atan2`).
#[inline(always)]
pub fn atan_over(t2: f64) -> f64 {
    // Horner's scheme from the t²⁴ term down: 1/25, then c + t²·(…) for c = −1/23 … 1.
    const C: [f64; 12] = [
        -1.0 / 23.0,
        1.0 / 21.0,
        -1.0 / 19.0,
        1.0 / 17.0,
        -1.0 / 15.0,
        1.0 / 13.0,
        -1.0 / 11.0,
        1.0 / 9.0,
        -1.0 / 7.0,
        1.0 / 5.0,
        -1.0 / 3.0,
        1.0,
    ];
    C.iter().fold(1.0 / 25.0, |p, c| c + t2 * p)
}

/// `1/√x`, computed as `√x · (1/x)`.
///
/// The root and the reciprocal do not wait for each other, so the processor runs them side
/// by side (docs/PERFORMANCE.md has the measurement); every filter's update has one or
/// two on its critical path.
/// Three correctly rounded operations: within 1.5 ulp of `1/√x`, against 1 ulp for the
/// root then the division. Outside `[1e-300, 1e300]`, where `1/x` would be subnormal or
/// infinite, it is `1.0 / x.sqrt()`.
#[inline]
pub fn inv_sqrt(x: f64) -> f64 {
    match inv_sqrt_fast(x) {
        Some(r) => r,
        None => inv_sqrt_outside(x),
    }
}

/// [`inv_sqrt`], or `None` when `x` is zero, negative or not finite. The usual case costs
/// the same two comparisons as `inv_sqrt`'s; the others are told apart out of line.
#[inline]
pub(crate) fn try_inv_sqrt(x: f64) -> Option<f64> {
    match inv_sqrt_fast(x) {
        Some(r) => Some(r),
        None => try_inv_sqrt_outside(x),
    }
}

/// `√x · (1/x)` when `x` lies in `[1e-300, 1e300]`, the range where it is used.
#[inline(always)]
pub(crate) fn inv_sqrt_fast(x: f64) -> Option<f64> {
    if in_fast_range(x) {
        Some(inv_sqrt_in_range(x))
    } else {
        None
    }
}

/// [`inv_sqrt_fast`] on every lane of `x` (one filter's `f64`, or filters side by side):
/// `None` unless every lane is in the range.
#[inline(always)]
pub(crate) fn inv_sqrt_fast_lanes<T: lanes::Real>(x: T) -> Option<T> {
    (x.decide(in_fast_range) == Some(true)).then(|| inv_sqrt_in_range(x))
}

/// The range `(1e-300, 1e300)` of [`inv_sqrt_fast`].
#[inline(always)]
fn in_fast_range(x: f64) -> bool {
    x > 1e-300 && x < 1e300
}

/// [`inv_sqrt_fast`] for an `x` the caller knows to be below 1e300 (a squared norm that
/// the bounds on accepted readings and on the settings keep small): the lower test only.
/// The same result wherever that holds; a NaN still gives `None`.
#[inline(always)]
pub(crate) fn inv_sqrt_fast_bounded(x: f64) -> Option<f64> {
    debug_assert!(x < 1e300 || x.is_nan(), "{x}");
    if x > 1e-300 {
        Some(inv_sqrt_in_range(x))
    } else {
        None
    }
}

/// [`inv_sqrt`] for an `x` the caller has already found in `(1e-300, 1e300)`: the same
/// bits, without the test; on every lane for filters side by side.
#[inline(always)]
pub(crate) fn inv_sqrt_in_range<T: lanes::Real>(x: T) -> T {
    x.sqrt() * (T::of(1.0) / x)
}

#[cold]
#[inline(never)]
fn try_inv_sqrt_outside(x: f64) -> Option<f64> {
    (x.is_finite() && x > 0.0).then(|| inv_sqrt_outside(x))
}

/// Out of line, so the compiler does not compute it for every call and select (which put
/// a third operation on the divider, shared by the root and the division).
#[cold]
#[inline(never)]
fn inv_sqrt_outside(x: f64) -> f64 {
    1.0 / x.sqrt()
}

/// A small deterministic generator for the unit tests (a 64-bit LCG): uniform in [−1, 1).
#[cfg(test)]
pub(crate) fn test_uniform(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed;
    move || {
        state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
}

#[cfg(test)]
mod tests {
    use super::{
        atan2, atan_over, cos_and_sinc, cos_minus_sinc_over_x2, cos_sin, inv_sqrt, one_minus_exp_neg,
        one_minus_exp_neg_libm,
    };

    /// [`cos_sin`] and [`atan2`] on both sides of their series' ranges: within 2ε relative
    /// (cosine and sine) or 2ε of the angle (atan2) of libm's, and libm's bits beyond.
    #[test]
    #[cfg_attr(miri, ignore = "long loops: too slow under Miri")]
    fn cos_sin_and_atan2_are_libms() {
        let mut u = super::test_uniform(53);
        for _ in 0..20000 {
            let x = u() * 10f64.powf(-9.0 + 9.5 * 0.5 * (u() + 1.0));
            let ((c, s), (s0, c0)) = (cos_sin(x), libm::sincos(x));
            if x * x < 1.0 / 256.0 {
                assert!((c - c0).abs() <= 2.0 * f64::EPSILON * c0.abs(), "cos {x:e}");
                assert!((s - s0).abs() <= 2.0 * f64::EPSILON * s0.abs(), "sin {x:e}");
            } else {
                assert_eq!((c.to_bits(), s.to_bits()), (c0.to_bits(), s0.to_bits()), "{x:e}");
            }
            let (y, xx) = (x, 10f64.powf(u()));
            let (a, a0) = (atan2(y, xx), libm::atan2(y, xx));
            if 4.0 * y.abs() < xx {
                assert!((a - a0).abs() <= 2.0 * f64::EPSILON * a0.abs(), "atan2 {y:e} {xx:e}");
            } else {
                assert_eq!(a.to_bits(), a0.to_bits(), "{y:e} {xx:e}");
            }
        }
        assert_eq!(atan2(1.0, -4.0).to_bits(), libm::atan2(1.0, -4.0).to_bits());
        assert_eq!(atan2(-0.0, 1.0).to_bits(), (-0.0f64).to_bits());
    }

    /// The series for `(cos x − sin x / x) / x²` over its range (x² from 1e-12 to 1/256):
    /// within 2ε of the same series to the 38th power, summed from its smallest term
    /// up (the terms it leaves out are below 1.8e-21); within 4ε/x² of libm's
    /// `(cos x − sin x / x) / x²`, whose cancellation leaves about that (x² ≥ 1/1024, where
    /// the bound is under 1e-12); `C − A = B x²` with [`cos_and_sinc`]; and −1/3 at 0.
    #[test]
    #[cfg_attr(miri, ignore = "long loops: too slow under Miri")]
    fn cos_minus_sinc_over_x2_series() {
        let mut u = super::test_uniform(47);
        for i in 0..20000 {
            let x2 = if i == 0 {
                1.0 / 256.0
            } else {
                10f64.powf(-12.0 + (12.0 - 256f64.log10()) * 0.5 * (u() + 1.0))
            };
            let b = cos_minus_sinc_over_x2(x2);
            // Σ_{k=1..20} (−1)ᵏ 2k x²⁽ᵏ⁻¹⁾ / (2k + 1)!, smallest term first.
            let terms: Vec<f64> = (1..=20)
                .scan(1.0 / 6.0, |f, k| {
                    let term = (-1f64).powi(k) * 2.0 * k as f64 * *f * x2.powi(k - 1);
                    *f /= ((2 * k + 2) * (2 * k + 3)) as f64;
                    Some(term)
                })
                .collect();
            let long = terms.iter().rev().sum::<f64>();
            assert!((b - long).abs() <= 2.0 * f64::EPSILON * long.abs(), "{x2:e}: {b:e} vs {long:e}");
            if x2 >= 1.0 / 1024.0 {
                let x = x2.sqrt();
                let direct = (libm::cos(x) - libm::sin(x) / x) / x2;
                let (c, sinc) = cos_and_sinc(x2);
                assert!((b - direct).abs() <= 4.0 * f64::EPSILON / x2, "{x2:e}: {b:e} vs {direct:e}");
                assert!((c - sinc - b * x2).abs() <= 2.0 * f64::EPSILON, "{x2:e}");
            }
        }
        assert_eq!(cos_minus_sinc_over_x2(0.0), -1.0 / 3.0);
    }

    /// The series for `atan t / t` against libm's `atan2(t, 1)`, over its range
    /// (|t| ≤ 1/4, log-uniform, and the ends): within 2ε relative (2 to 4 ulp).
    #[test]
    #[cfg_attr(miri, ignore = "long loops: too slow under Miri")]
    fn atan_over_series_is_atan() {
        let mut u = super::test_uniform(43);
        for i in 0..20000 {
            let t = match i {
                0 => 0.25,
                1 => -0.25,
                2 => 1e-300,
                _ => u().signum() * 10f64.powf(-12.0 + (12.0 - 4f64.log10()) * 0.5 * (u() + 1.0)),
            };
            let (got, want) = (t * atan_over(t * t), libm::atan2(t, 1.0));
            assert!((got - want).abs() <= 2.0 * f64::EPSILON * want.abs(), "{t:e}: {got:e} vs {want:e}");
        }
    }

    /// The series for `1 − e^{−x}` against libm's `−expm1(−x)`, over its range (x from
    /// 1e-12 to 1/8, log-uniform, and the ends): within 2⁻⁵¹ relative. Against 200-bit
    /// arithmetic (mpmath, 30,000 x) the series is within 0.73 units of 2⁻⁵² and expm1
    /// within 0.51, so the bound is their two errors. Outside the range it is libm's.
    #[test]
    #[cfg_attr(miri, ignore = "long loops: too slow under Miri")]
    fn one_minus_exp_neg_series_is_expm1() {
        let mut u = super::test_uniform(41);
        let mut worst = 0.0f64;
        for i in 0..20000 {
            let x = match i {
                0 => 0.0,
                1 => f64::MIN_POSITIVE,
                2 => 0.125 - f64::EPSILON / 8.0,
                _ => 10f64.powf(-12.0 + (12.0 - 8f64.log10()) * 0.5 * (u() + 1.0)),
            };
            let (got, want) = (one_minus_exp_neg(x), one_minus_exp_neg_libm(x));
            if want != 0.0 {
                worst = worst.max((got - want).abs() / want);
            } else {
                assert_eq!(got, 0.0);
            }
        }
        assert!(worst <= 2.0 * f64::EPSILON, "{worst:e}");
        for x in [0.125, 0.5, 3.0, 1e6, -1e-3, f64::INFINITY] {
            assert_eq!(one_minus_exp_neg(x).to_bits(), (-libm::expm1(-x)).to_bits(), "{x}");
        }
        assert!(one_minus_exp_neg(f64::NAN).is_nan());
    }

    /// `libm::sincos` gives `libm::sin`'s and `libm::cos`'s bits (the robust kind and the
    /// EKF rely on it), over arguments of every size and sign.
    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn sincos_is_sin_and_cos_to_the_bit() {
        let mut r = super::test_uniform(13);
        for i in 0..100_000 {
            let x = r() * [1e-9, 0.1, 1.0, 4.0, 40.0, 1e6][i % 6];
            let (s, c) = libm::sincos(x);
            assert_eq!((s.to_bits(), c.to_bits()), (libm::sin(x).to_bits(), libm::cos(x).to_bits()), "{x}");
        }
        // The robust kind skips the call for a zero angle: (±0, 1) are its bits.
        for x in [0.0, -0.0f64] {
            let (s, c) = libm::sincos(x);
            assert_eq!((s.to_bits(), c.to_bits()), (x.to_bits(), 1.0f64.to_bits()), "{x}");
        }
    }

    #[test]
    fn inv_sqrt_is_within_two_ulp_inside_and_exact_outside_its_range() {
        for x in [1e-299, 3e-150, 1e-9, 0.37, 1.0, 1.0 + 2e-16, 2.0, 9.80665f64.powi(2), 6.2e17, 9e299] {
            let (fast, plain) = (inv_sqrt(x), 1.0 / x.sqrt());
            assert!((fast - plain).abs() <= 2.0 * f64::EPSILON * plain, "{x}: {fast} vs {plain}");
        }
        // Outside [1e-300, 1e300] 1/x would be subnormal or infinite: the plain form.
        for x in [1e-310, 5e-301, 2e300, f64::MAX] {
            assert_eq!(inv_sqrt(x).to_bits(), (1.0 / x.sqrt()).to_bits(), "{x}");
        }
    }
}
