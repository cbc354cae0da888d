//! Four f64 lanes as one value, for code that runs in both the baseline and the AVX
//! copy (`crate::isa`): [`Lanes`] is what such code asks of its lane type.
//!
//! The baseline type is the `wide` crate's `f64x4` (two SSE2 registers on x86-64's
//! baseline); the AVX copy uses `crate::isa::Avx4` (one 256-bit register), which the
//! `wide` crate cannot give there because it picks its representation when it is
//! compiled. Every operation is the IEEE operation lane by lane, so both give the same
//! bits.
//!
//! Values are made from a [`Lanes::Token`]: `()` for `f64x4`, and for `Avx4` a token
//! that only exists on a CPU with AVX. Code with a value at hand takes the token from it
//! ([`Lanes::token`]).
//!
//! [`Real`] is the other use of lanes here: what a step written once for one filter
//! (`f64`) and for two filters side by side ([`F64x2`]) asks of its number type
//! (Madgwick's update and the rig's pairs).

use core::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Sub, SubAssign};
use wide::{f64x2, f64x4};

/// Four f64 lanes with lane-wise IEEE arithmetic.
pub trait Lanes:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign
    + DivAssign
{
    /// What making a value needs (see the module's documentation).
    type Token: Copy;
    /// The lanes `v`.
    fn new(t: Self::Token, v: [f64; 4]) -> Self;
    /// Every lane `x`.
    fn splat(t: Self::Token, x: f64) -> Self;
    /// The lanes as an array.
    fn to_array(self) -> [f64; 4];
    /// The token this value was made with.
    fn token(self) -> Self::Token;
    /// The same lanes from the stored form.
    #[inline(always)]
    fn load(t: Self::Token, v: f64x4) -> Self {
        Self::new(t, v.to_array())
    }
    /// The stored form.
    #[inline(always)]
    fn store(self) -> f64x4 {
        f64x4::new(self.to_array())
    }
}

impl Lanes for f64x4 {
    type Token = ();
    #[inline(always)]
    fn new(_: (), v: [f64; 4]) -> f64x4 {
        f64x4::new(v)
    }
    #[inline(always)]
    fn splat(_: (), x: f64) -> f64x4 {
        f64x4::splat(x)
    }
    #[inline(always)]
    fn to_array(self) -> [f64; 4] {
        f64x4::to_array(self)
    }
    #[inline(always)]
    fn token(self) {}
    #[inline(always)]
    fn load(_: (), v: f64x4) -> f64x4 {
        v
    }
    #[inline(always)]
    fn store(self) -> f64x4 {
        self
    }
}

/// The arithmetic of a step written once for one filter (`f64`) and for two filters at
/// once ([`F64x2`], one filter per lane): Madgwick's update and its lane form come from
/// the same source (`filters::madgwick`). Every operation, negation included, is the IEEE
/// operation lane by lane, so each lane gives the bits `f64` gives.
pub(crate) trait Real:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + core::ops::Neg<Output = Self>
{
    /// `x` in every lane.
    fn of(x: f64) -> Self;
    fn sqrt(self) -> Self;
    /// `Some(true)` when `f` holds in every lane, `Some(false)` when in none, `None` when
    /// the lanes differ (a step then leaves them to the one-filter path).
    fn decide(self, f: impl Fn(f64) -> bool) -> Option<bool>;
}

impl Real for f64 {
    #[inline(always)]
    fn of(x: f64) -> f64 {
        x
    }
    #[inline(always)]
    fn sqrt(self) -> f64 {
        f64::sqrt(self)
    }
    #[inline(always)]
    fn decide(self, f: impl Fn(f64) -> bool) -> Option<bool> {
        Some(f(self))
    }
}

/// Two f64 lanes in `wide`'s `f64x2` (one SSE2 or NEON register). A type of its own for
/// the negation: `wide` negates as `0 − x`, which gives +0 for +0 where IEEE negation
/// gives −0; here `−x` is `−0 − x`, the IEEE negation of every value but NaN.
#[derive(Clone, Copy, Debug)]
pub(crate) struct F64x2(f64x2);

impl F64x2 {
    /// The number of lanes.
    pub(crate) const LANES: usize = 2;

    #[inline(always)]
    pub(crate) fn new(v: [f64; Self::LANES]) -> F64x2 {
        F64x2(f64x2::new(v))
    }
    #[inline(always)]
    pub(crate) fn to_array(self) -> [f64; Self::LANES] {
        self.0.to_array()
    }
}

macro_rules! pair_op {
    ($tr:ident, $f:ident, $op:tt) => {
        impl $tr for F64x2 {
            type Output = F64x2;
            #[inline(always)]
            fn $f(self, o: F64x2) -> F64x2 {
                F64x2(self.0 $op o.0)
            }
        }
    };
}
pair_op!(Add, add, +);
pair_op!(Sub, sub, -);
pair_op!(Mul, mul, *);
pair_op!(Div, div, /);

impl core::ops::Neg for F64x2 {
    type Output = F64x2;
    #[inline(always)]
    fn neg(self) -> F64x2 {
        F64x2(f64x2::splat(-0.0) - self.0)
    }
}

impl Real for F64x2 {
    #[inline(always)]
    fn of(x: f64) -> F64x2 {
        F64x2(f64x2::splat(x))
    }
    #[inline(always)]
    fn sqrt(self) -> F64x2 {
        F64x2(self.0.sqrt())
    }
    #[inline(always)]
    fn decide(self, f: impl Fn(f64) -> bool) -> Option<bool> {
        let [a, b] = self.to_array().map(f);
        (a == b).then_some(a)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pair_arithmetic_is_f64s_lane_by_lane_including_the_sign_of_zero() {
        let values = [0.0, -0.0, 1.5, -2.25, 1e-310, f64::INFINITY, f64::NEG_INFINITY, 3.0e300];
        // Bits, with every NaN alike: a NaN's sign and payload are not specified (Miri
        // picks them at random).
        let bits = |v: [f64; 2]| v.map(|x| if x.is_nan() { f64::NAN.to_bits() } else { x.to_bits() });
        for &x in &values {
            for &y in &values {
                let (a, b) = (F64x2::new([x, y]), F64x2::new([y, x]));
                assert_eq!(bits((-a).to_array()), bits([-x, -y]), "-{x} -{y}");
                assert_eq!(bits((a + b).to_array()), bits([x + y, y + x]));
                assert_eq!(bits((a - b).to_array()), bits([x - y, y - x]));
                assert_eq!(bits((a * b).to_array()), bits([x * y, y * x]));
                if y != 0.0 && x != 0.0 {
                    assert_eq!(bits((a / b).to_array()), bits([x / y, y / x]));
                }
                assert_eq!(
                    bits(F64x2::new([x.abs(), y.abs()]).sqrt().to_array()),
                    bits([x.abs().sqrt(), y.abs().sqrt()])
                );
            }
        }
        assert_eq!(F64x2::new([1.0, 2.0]).decide(|v| v > 0.0), Some(true));
        assert_eq!(F64x2::new([-1.0, -2.0]).decide(|v| v > 0.0), Some(false));
        assert_eq!(F64x2::new([1.0, -2.0]).decide(|v| v > 0.0), None);
    }
}
