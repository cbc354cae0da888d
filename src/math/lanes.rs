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

/// The arithmetic of a step written once for one filter (`f64`) and for four filters at
/// once (`f64x4`, one filter per lane): Madgwick's update and its four-lane form come from
/// the same source (`filters::madgwick`). Every operation is the IEEE operation lane by
/// lane, so each lane gives the bits `f64` gives.
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

/// [`Real`] for a `wide` lane type: one filter per lane.
macro_rules! real_lanes {
    ($($t:ident),*) => {$(
        impl Real for $t {
            #[inline(always)]
            fn of(x: f64) -> $t {
                $t::splat(x)
            }
            #[inline(always)]
            fn sqrt(self) -> $t {
                $t::sqrt(self)
            }
            #[inline(always)]
            fn decide(self, f: impl Fn(f64) -> bool) -> Option<bool> {
                let v = self.to_array().map(f);
                v.iter().all(|x| *x == v[0]).then_some(v[0])
            }
        }
    )*};
}
real_lanes!(f64x2, f64x4);
