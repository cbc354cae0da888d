#!/usr/bin/env bash
# Installs what building and testing orient needs on a Debian machine: a C/C++
# toolchain, binutils (nm, readelf), CMake and pkg-config (packaging tests), Mono's
# compiler and runtime (C# binding tests) and abi-compliance-checker from apt; Rust
# through rustup when cargo is missing; the pinned cbindgen 0.29.4 from crates.io.
# With --cross, also the Linux board targets (aarch64, armv7): their Rust standard
# libraries, Debian's cross compilers and qemu-user. Safe to run again.
set -euo pipefail
cd "$(dirname "$0")/.."
cross=0
[ "${1:-}" = "--cross" ] && cross=1

sudo=""
if [ "$(id -u)" != 0 ]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends \
  build-essential binutils ca-certificates curl pkg-config cmake \
  mono-mcs mono-runtime abi-compliance-checker valgrind >/dev/null

if ! command -v cargo >/dev/null 2>&1; then
  if [ -x "$HOME/.cargo/bin/cargo" ]; then
    export PATH="$HOME/.cargo/bin:$PATH"
  else
    curl -sSf https://sh.rustup.rs | sh -s -- -y --profile minimal --component rustfmt,clippy
    export PATH="$HOME/.cargo/bin:$PATH"
  fi
fi
export PATH="$HOME/.cargo/bin:$PATH"

if [ "$(cbindgen --version 2>/dev/null || true)" != "cbindgen 0.29.4" ]; then
  cargo install cbindgen --locked --version 0.29.4 --quiet
fi
# Nightly with Miri (the FFI's unsafe code under Miri) and cargo-fuzz (fuzzing the C ABI).
if ! rustup component list --toolchain nightly --installed 2>/dev/null | grep -q '^miri'; then
  rustup toolchain install nightly --profile minimal --component miri,rust-src >/dev/null 2>&1 ||
    rustup toolchain install nightly --profile minimal --component miri,rust-src
fi
if ! command -v cargo-fuzz >/dev/null 2>&1; then
  cargo install cargo-fuzz --locked --quiet
fi

if [ "$cross" = 1 ]; then
  $sudo apt-get install -y -qq --no-install-recommends \
    gcc-aarch64-linux-gnu g++-aarch64-linux-gnu gcc-arm-linux-gnueabihf g++-arm-linux-gnueabihf \
    libc6-dev-arm64-cross libc6-dev-armhf-cross qemu-user >/dev/null
  rustup target add aarch64-unknown-linux-gnu armv7-unknown-linux-gnueabihf >/dev/null 2>&1 ||
    rustup target add aarch64-unknown-linux-gnu armv7-unknown-linux-gnueabihf
fi
echo "setup: $(cargo --version), $(cbindgen --version), $(cc --version | head -n 1)"
