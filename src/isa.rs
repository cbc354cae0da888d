//! Runs the filters' arithmetic in the widest instruction encoding the CPU has.
//!
//! The library is built for the x86-64 baseline (SSE2) so that it loads on every x86-64
//! host. On a CPU with AVX, [`widest`] runs its closure in a copy of the code compiled
//! with AVX enabled: the same IEEE operations in the same order (no FMA, so nothing is
//! contracted), hence the same bits, in VEX's three-operand form, which needs no
//! register copies. Everywhere else (other architectures, CPUs without AVX, Miri) the
//! closure runs as it is.
//!
//! Setting the environment variable `ORIENT_ISA=baseline` before the first update
//! keeps the baseline code on any CPU: for tools that do not decode every AVX
//! instruction (valgrind 3.19 stops at a register-to-register `vmovq`), and to compare.
//!
//! This is the one place outside `ffi` with `unsafe`: calling a function compiled for a
//! feature the CPU may lack is undefined behaviour, so the call sits behind the
//! run-time check.

/// Runs `f`, compiled for AVX when this CPU has it (see the module's documentation).
/// Whatever should run in the wide encoding must be inlined into `f`: mark the closure
/// and its callees `#[inline(always)]`; a function `f` calls out of line runs in the
/// baseline encoding.
#[inline(always)]
pub(crate) fn widest<R>(f: impl FnOnce() -> R) -> R {
    #[cfg(all(target_arch = "x86_64", not(target_feature = "avx"), not(miri)))]
    if *AVX {
        // SAFETY: `with_avx` needs AVX, and the CPU has it (AVX is true only then).
        return unsafe { with_avx(f) };
    }
    f()
}

/// Whether [`widest`] takes the AVX copy: the CPU has AVX and `ORIENT_ISA` is not
/// `baseline`. Read once.
#[cfg(all(target_arch = "x86_64", not(target_feature = "avx"), not(miri)))]
static AVX: once_cell::sync::Lazy<bool> = once_cell::sync::Lazy::new(|| {
    std::arch::is_x86_feature_detected!("avx")
        && std::env::var_os("ORIENT_ISA").map_or(true, |v| v != "baseline")
});

#[cfg(all(target_arch = "x86_64", not(target_feature = "avx"), not(miri)))]
#[target_feature(enable = "avx")]
unsafe fn with_avx<R>(f: impl FnOnce() -> R) -> R {
    f()
}
