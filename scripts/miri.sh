#!/usr/bin/env bash
# Miri on the unit tests of the code that Miri is there for: the unsafe code.
#   - src/ffi: every C entry point reads and writes through raw pointers, turns handles
#     back into filters, and catches panics at the boundary; its tests (ffi::tests and
#     the submodules') call the entry points as C would, with good, null, freed, copied
#     and forged handles. ffi::registry is safe code (the handle table's bookkeeping; its
#     collision test alone took 65 s of Miri's 117) and runs natively in `cargo test`.
#   - math::lanes: the explicit f64x4 lanes, where orient's arithmetic meets the SIMD
#     intrinsics inside `wide` (unsafe code in a dependency, cheap to keep).
# The rest of the crate is `#![forbid(unsafe_code)]` (math, filters, offline) and its
# unit tests run natively (`cargo test`) and under qemu (scripts/test-cross.sh); under
# Miri they took 100 of the 117 s and checked no unsafe line of ours. src/isa.rs's unsafe
# (the AVX copy) never runs under Miri, which reports no AVX; its test is native-only.
#   scripts/miri.sh [MORE LIBTEST ARGS]
set -euo pipefail
cd "$(dirname "$0")/.."
# Tree Borrows: nalgebra's matrix views break the stricter Stacked Borrows model
# inside nalgebra itself (cholesky -> gemv), which is not orient's code.
MIRIFLAGS="${MIRIFLAGS:--Zmiri-tree-borrows}" cargo +nightly miri test -p orient --lib -- \
  ffi:: math::lanes:: --skip ffi::registry:: "$@"
