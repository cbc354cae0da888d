#!/usr/bin/env bash
# Every test: setup, formatting, lints, the API documentation's links, the generated header and the exported
# symbols, the C# P/Invoke layer generated from the header, the ABI against its baseline, then cargo test: Rust unit and integration
# tests, doc tests, the C test program against the .so and the .a, the C++ wrapper
# (with and without exceptions), the C# binding under Mono and the Unity scripts
# against a stub, the examples in every language, the install layout with CMake and
# pkg-config consumers, golden vectors, and the BROAD recordings in ../shared/data;
# the Python package's sdist built into a wheel and tested with pytest in a fresh venv;
# the Conan recipe (conan create with its CMake consumer);
# then the same suite for aarch64 and armv7 under qemu-user (the golden vectors must
# match bit for bit there too); then the release for every platform, built with CI's
# lighter profile and checked: exports, glibc floor, Unity .meta files, the C ABI test
# under qemu and Wine, CMake and pkg-config, the C# tests under Mono full AOT
# (scripts/test-release.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup-debian.sh --cross
export PATH="$HOME/.cargo/bin:$PATH"

echo "== format"
cargo fmt --all -- --check
echo "== clippy"
cargo clippy --workspace --all-targets --quiet -- -D warnings
echo "== rustdoc (the library's API documentation, links included)"
RUSTDOCFLAGS="-D warnings" cargo doc -p orient --no-deps --quiet
echo "== header and exports"
scripts/check-header.sh
echo "== C# P/Invoke layer generated from the header"
scripts/check-csharp.sh
scripts/check-python-native.sh
echo "== ABI against the committed baseline"
scripts/check-abi.sh
echo "== cargo test (the library and the tools crate)"
cargo test
echo "== Python package: wheel, fresh virtual environment, pytest"
scripts/test-python.sh
echo "== Conan recipe: conan create and the test_package consumer"
scripts/test-conan.sh
echo "== Miri on the library's unit tests (unsafe FFI code included)"
# Tree Borrows: nalgebra's matrix views break the stricter Stacked Borrows model
# inside nalgebra itself (cholesky -> gemv), which is not orient's code.
MIRIFLAGS="-Zmiri-tree-borrows" cargo +nightly miri test -p orient --lib
echo "== fuzzing the C ABI (short run; scripts/fuzz.sh SECONDS for longer)"
scripts/fuzz.sh 60
for board in aarch64 armv7; do
  echo "== cargo test for $board under qemu"
  scripts/test-cross.sh "$board"
done
echo "== release for every platform (CI profile) and its checks"
scripts/test-release.sh
