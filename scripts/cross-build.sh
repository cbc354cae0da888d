#!/usr/bin/env bash
# One command for a board build: the release .so and .a for a Linux board target,
# stripped copies and their sizes, and the newest glibc symbol version the .so needs.
#   scripts/cross-build.sh aarch64|armv7 [OUT_DIR]
# (scripts/setup-debian.sh --cross installs the toolchains.)
set -euo pipefail
cd "$(dirname "$0")/.."
case "${1:-}" in
  aarch64) target=aarch64-unknown-linux-gnu prefix=aarch64-linux-gnu ;;
  armv7) target=armv7-unknown-linux-gnueabihf prefix=arm-linux-gnueabihf ;;
  *) echo "usage: $0 aarch64|armv7 [OUT_DIR]" >&2; exit 2 ;;
esac
out="${2:-target/$target/dist}"
cargo build --release --lib --target "$target"
mkdir -p "$out"
"$prefix-strip" --strip-unneeded -o "$out/liborient.so" "target/$target/release/liborient.so"
"$prefix-strip" --strip-debug -o "$out/liborient.a" "target/$target/release/liborient.a"
glibc=$("$prefix-objdump" -T "$out/liborient.so" | grep -o 'GLIBC_[0-9.]*' | sort -t. -k1,1 -k2,2n -k3,3n -V | tail -n 1)
echo "$target: liborient.so $(stat -c %s "$out/liborient.so") bytes, liborient.a $(stat -c %s "$out/liborient.a") bytes (stripped), needs up to $glibc"
echo "in $out"
