//! Runs the filters' arithmetic in the widest instruction encoding the CPU has.
//!
//! The library is built for the x86-64 baseline (SSE2) so that it loads on every x86-64
//! host. On a CPU with AVX, [`widest`] runs its closure in a copy of the code compiled
//! with AVX enabled: the same IEEE operations in the same order (no FMA, so nothing is
//! contracted), hence the same bits, in VEX's three-operand form, which needs no
//! register copies. Everywhere else (other architectures, CPUs without AVX, Miri) the
//! closure runs as it is.
//!
//! Setting the environment variable `ORIENT_ISA=baseline` before the first EKF or GMVDK
//! filter is made (the kinds that use this module, through [`prepare`]) keeps the
//! baseline code on any CPU: for tools that do not decode every AVX
//! instruction (valgrind 3.19 stops at a register-to-register `vmovq`), and to compare.
//!
//! [`widest_lanes`] does the same for code generic over its four-lane type, which it
//! runs with 256-bit AVX lanes ([`Avx4`]) in the AVX copy.
//!
//! This is the one place outside `ffi` with `unsafe`: calling a function compiled for a
//! feature the CPU may lack is undefined behaviour, so the call sits behind the
//! run-time check.

use crate::math::lanes::Lanes;

/// True where this build has an AVX copy for [`widest`] to take (x86-64 built for a
/// baseline without AVX, outside Miri): code that must be written differently for it to
/// be inlined there asks this, not the target itself.
pub(crate) const HAS_AVX_COPY: bool =
    cfg!(all(target_arch = "x86_64", not(target_feature = "avx"), not(miri)));

/// Runs `f`, compiled for AVX when this CPU has it (see the module's documentation).
/// Whatever should run in the wide encoding must be inlined into `f`: mark the closure
/// and its callees `#[inline(always)]`; a function `f` calls out of line runs in the
/// baseline encoding.
#[inline(always)]
pub(crate) fn widest<R>(f: impl FnOnce() -> R) -> R {
    #[cfg(all(target_arch = "x86_64", not(target_feature = "avx"), not(miri)))]
    if use_avx() {
        // SAFETY: `with_avx` needs AVX, and the CPU has it (use_avx() is true only then).
        return unsafe { with_avx(f) };
    }
    f()
}

/// Whether [`widest`] takes the AVX copy: [`UNKNOWN`] until [`prepare`] decides, then
/// [`BASELINE`] or [`WIDE`] (the CPU has AVX and `ORIENT_ISA` is not `baseline`). A plain
/// atomic byte decided when a filter is made, rather than a lazily initialised cell
/// decided at the first update: every update reads it, and the read is then one load and
/// one comparison (the cell's took two of each). Threads that decide at the same time
/// store the same value, so relaxed ordering suffices.
#[cfg(all(target_arch = "x86_64", not(target_feature = "avx"), not(miri)))]
static AVX: core::sync::atomic::AtomicU8 = core::sync::atomic::AtomicU8::new(UNKNOWN);
#[cfg(all(target_arch = "x86_64", not(target_feature = "avx"), not(miri)))]
const UNKNOWN: u8 = 0;
#[cfg(all(target_arch = "x86_64", not(target_feature = "avx"), not(miri)))]
const BASELINE: u8 = 1;
#[cfg(all(target_arch = "x86_64", not(target_feature = "avx"), not(miri)))]
const WIDE: u8 = 2;

/// Decides whether [`widest`] takes the AVX copy, once per process (later calls return at
/// the first test). The kinds that run through [`widest`] call it when a filter is made;
/// until it has run, [`widest`] takes the baseline copy, which gives the same bits.
#[inline]
pub(crate) fn prepare() {
    #[cfg(all(target_arch = "x86_64", not(target_feature = "avx"), not(miri)))]
    if AVX.load(core::sync::atomic::Ordering::Relaxed) == UNKNOWN {
        decide_avx();
    }
}

#[cfg(all(target_arch = "x86_64", not(target_feature = "avx"), not(miri)))]
#[cold]
#[inline(never)]
fn decide_avx() {
    let wide = std::arch::is_x86_feature_detected!("avx")
        && std::env::var_os("ORIENT_ISA").map_or(true, |v| v != "baseline");
    AVX.store(if wide { WIDE } else { BASELINE }, core::sync::atomic::Ordering::Relaxed);
}

/// Whether to take the AVX copy: [`AVX`], unless a unit test asked for the baseline.
#[cfg(all(target_arch = "x86_64", not(target_feature = "avx"), not(miri)))]
#[inline(always)]
fn use_avx() -> bool {
    #[cfg(test)]
    if FORCE_BASELINE.with(|f| f.get()) {
        return false;
    }
    AVX.load(core::sync::atomic::Ordering::Relaxed) == WIDE
}

#[cfg(test)]
thread_local! {
    static FORCE_BASELINE: core::cell::Cell<bool> = const { core::cell::Cell::new(false) };
}

/// Runs `f` with the baseline code on this thread (unit tests: the AVX copy must give the
/// same bits).
#[cfg(test)]
pub(crate) fn baseline<R>(f: impl FnOnce() -> R) -> R {
    FORCE_BASELINE.with(|b| b.set(true));
    let r = f();
    FORCE_BASELINE.with(|b| b.set(false));
    r
}

#[cfg(all(target_arch = "x86_64", not(target_feature = "avx"), not(miri)))]
#[target_feature(enable = "avx")]
unsafe fn with_avx<R>(f: impl FnOnce() -> R) -> R {
    f()
}

/// Code generic over its four-lane type ([`Lanes`]): [`widest_lanes`] runs it with the
/// widest type the CPU has.
pub(crate) trait WithLanes {
    type Out;
    /// Runs with lane type `V`, whose values are made with `t`.
    fn run<V: Lanes>(self, t: V::Token) -> Self::Out;
}

/// Runs `w` in the AVX copy with 256-bit lanes ([`Avx4`]) when this CPU has AVX (as
/// [`widest`]), otherwise with the baseline `wide::f64x4`. Mark `run` `#[inline(always)]`.
#[inline(always)]
pub(crate) fn widest_lanes<W: WithLanes>(w: W) -> W::Out {
    #[cfg(all(target_arch = "x86_64", not(target_feature = "avx"), not(miri)))]
    if use_avx() {
        // SAFETY: as in `widest`; the token says the same to the lanes' operations.
        return unsafe {
            with_avx(
                #[inline(always)]
                || w.run::<Avx4>(AvxToken(())),
            )
        };
    }
    w.run::<wide::f64x4>(())
}

#[cfg(all(target_arch = "x86_64", not(target_feature = "avx"), not(miri)))]
pub(crate) use avx4::{Avx4, AvxToken};

/// Four lanes in one AVX register. A value exists only on a CPU with AVX: making one
/// takes an [`AvxToken`], which only [`widest_lanes`] makes, after the check; so every
/// operation below may use AVX instructions. They are meant to be inlined into the AVX
/// copy (`with_avx`), where the intrinsics become single instructions.
#[cfg(all(target_arch = "x86_64", not(target_feature = "avx"), not(miri)))]
mod avx4 {
    use crate::math::lanes::Lanes;
    use core::arch::x86_64::{
        __m256d, _mm256_add_pd, _mm256_div_pd, _mm256_loadu_pd, _mm256_mul_pd, _mm256_set1_pd,
        _mm256_storeu_pd, _mm256_sub_pd,
    };
    use core::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Sub, SubAssign};

    /// Proof that this CPU has AVX.
    #[derive(Clone, Copy)]
    pub(crate) struct AvxToken(pub(super) ());

    #[derive(Clone, Copy)]
    pub(crate) struct Avx4(__m256d);

    impl Lanes for Avx4 {
        type Token = AvxToken;
        #[inline(always)]
        fn new(_: AvxToken, v: [f64; 4]) -> Avx4 {
            // SAFETY: the token says the CPU has AVX; `v` is four readable f64.
            Avx4(unsafe { _mm256_loadu_pd(v.as_ptr()) })
        }
        #[inline(always)]
        fn splat(_: AvxToken, x: f64) -> Avx4 {
            // SAFETY: the token says the CPU has AVX.
            Avx4(unsafe { _mm256_set1_pd(x) })
        }
        #[inline(always)]
        fn to_array(self) -> [f64; 4] {
            let mut v = [0.0; 4];
            // SAFETY: this value exists, so the CPU has AVX; `v` is four writable f64.
            unsafe { _mm256_storeu_pd(v.as_mut_ptr(), self.0) };
            v
        }
        #[inline(always)]
        fn token(self) -> AvxToken {
            AvxToken(())
        }
    }

    macro_rules! op {
        ($tr:ident, $f:ident, $tra:ident, $fa:ident, $intr:ident) => {
            impl $tr for Avx4 {
                type Output = Avx4;
                #[inline(always)]
                fn $f(self, o: Avx4) -> Avx4 {
                    // SAFETY: these values exist, so the CPU has AVX.
                    Avx4(unsafe { $intr(self.0, o.0) })
                }
            }
            impl $tra for Avx4 {
                #[inline(always)]
                fn $fa(&mut self, o: Avx4) {
                    *self = $tr::$f(*self, o);
                }
            }
        };
    }
    op!(Add, add, AddAssign, add_assign, _mm256_add_pd);
    op!(Sub, sub, SubAssign, sub_assign, _mm256_sub_pd);
    op!(Mul, mul, MulAssign, mul_assign, _mm256_mul_pd);
    op!(Div, div, DivAssign, div_assign, _mm256_div_pd);
}

#[cfg(all(test, target_arch = "x86_64", not(target_feature = "avx"), not(miri)))]
mod tests {
    use super::{AVX, BASELINE, UNKNOWN, WIDE};
    use core::sync::atomic::Ordering::Relaxed;

    /// `prepare` (which the kinds that run through `widest` call when a filter is made)
    /// decides the copy, as this CPU and `ORIENT_ISA` say.
    #[test]
    fn prepare_decides_the_copy() {
        super::prepare();
        let wide = std::arch::is_x86_feature_detected!("avx")
            && std::env::var_os("ORIENT_ISA").map_or(true, |v| v != "baseline");
        assert_ne!(AVX.load(Relaxed), UNKNOWN);
        assert_eq!(AVX.load(Relaxed), if wide { WIDE } else { BASELINE });
    }
}
