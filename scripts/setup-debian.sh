#!/usr/bin/env bash
# Installs what orient needs on a Debian machine. Safe to run again.
#   scripts/setup-debian.sh --demo    a C toolchain and Rust (through rustup when cargo is
#                                     missing): enough to build and run the demo
#   scripts/setup-debian.sh           everything the tests use: also binutils, CMake,
#                                     pkg-config, Mono (C# tests), valgrind,
#                                     abi-compliance-checker, python3 and python3-venv
#                                     (Python package tests) from apt; cbindgen 0.29.4 from
#                                     crates.io; nightly with Miri and cargo-fuzz
#   scripts/setup-debian.sh --cross   all of that plus the Linux board targets (aarch64,
#                                     armv7): Rust standard libraries, Debian's cross
#                                     compilers and qemu-user; and what scripts/release.sh
#                                     and scripts/test-release.sh use: the Rust standard
#                                     libraries of every release target, llvm-tools,
#                                     mingw-w64, Wine, LLVM 14 (lipo, dlltool), and zig
#                                     with cargo-zigbuild from PyPI (pinned) in a venv
set -euo pipefail
cd "$(dirname "$0")/.."
mode="${1:-tests}"

sudo=""
if [ "$(id -u)" != 0 ]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends build-essential ca-certificates curl >/dev/null

if ! command -v cargo >/dev/null 2>&1 && [ ! -x "$HOME/.cargo/bin/cargo" ]; then
  curl -sSf https://sh.rustup.rs | sh -s -- -y --profile minimal --component rustfmt,clippy
fi
export PATH="$HOME/.cargo/bin:$PATH"
if [ "$mode" = "--demo" ]; then
  echo "setup (demo): $(cargo --version), $(cc --version | head -n 1)"
  exit 0
fi

$sudo apt-get install -y -qq --no-install-recommends \
  binutils pkg-config cmake mono-mcs mono-runtime abi-compliance-checker valgrind >/dev/null
# The Python package's tests: python3 with venv (Debian splits it out); the test
# requirements themselves come from PyPI into a fresh virtual environment.
$sudo apt-get install -y -qq --no-install-recommends python3 python3-venv >/dev/null

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

if [ "$mode" = "--cross" ]; then
  $sudo apt-get install -y -qq --no-install-recommends \
    gcc-aarch64-linux-gnu g++-aarch64-linux-gnu gcc-arm-linux-gnueabihf g++-arm-linux-gnueabihf \
    libc6-dev-arm64-cross libc6-dev-armhf-cross qemu-user \
    gcc-mingw-w64-x86-64 g++-mingw-w64-x86-64 wine64 llvm python3 python3-venv >/dev/null
  targets="aarch64-unknown-linux-gnu armv7-unknown-linux-gnueabihf x86_64-unknown-linux-musl
    aarch64-unknown-linux-musl x86_64-pc-windows-gnu aarch64-apple-darwin x86_64-apple-darwin
    aarch64-apple-ios aarch64-linux-android armv7-linux-androideabi"
  # shellcheck disable=SC2086
  rustup target add $targets >/dev/null 2>&1 || rustup target add $targets
  rustup component add llvm-tools >/dev/null 2>&1 || rustup component add llvm-tools
  # zig links the Linux builds against glibc 2.17 (cargo-zigbuild's .2.17 target suffix)
  # and provides the macOS libSystem stub; pinned, in a venv of their own.
  tools="$HOME/.local/orient-tools"
  if [ ! -x "$tools/bin/cargo-zigbuild" ] || ! "$tools/bin/python3" -m ziglang version 2>/dev/null | grep -qx 0.15.2; then
    python3 -m venv "$tools"
    "$tools/bin/pip" install --quiet ziglang==0.15.2 cargo-zigbuild==0.24.1
  fi
fi
echo "setup: $(cargo --version), $(cbindgen --version), $(cc --version | head -n 1)"
