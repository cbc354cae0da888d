#!/usr/bin/env bash
# The whole test suite for a Linux board target under qemu-user: Rust tests, the C
# and C++ test programs (started through qemu), golden vectors bit for bit, the BROAD
# recordings. Host-only parts (Mono, CMake/pkg-config consumers) say they are skipped.
#   scripts/test-cross.sh aarch64|armv7
set -euo pipefail
cd "$(dirname "$0")/.."
case "${1:-}" in
  aarch64) target=aarch64-unknown-linux-gnu ;;
  armv7) target=armv7-unknown-linux-gnueabihf ;;
  *) echo "usage: $0 aarch64|armv7" >&2; exit 2 ;;
esac
cargo test --target "$target"
