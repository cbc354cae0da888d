#!/usr/bin/env bash
# Instruction counts per Madgwick MARG update in f64 and f32 on the emulated board
# targets (tools/src/bin/precision_cost.rs): qemu in single-step mode logs one line per
# executed instruction; a run of N updates minus a run of none, divided by N.
# Counts, not times: emulation says nothing about a board's clock.
#   scripts/instruction-counts.sh [N]        (default 2000; needs --cross setup)
set -euo pipefail
cd "$(dirname "$0")/.."
n="${1:-2000}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for spec in "aarch64-unknown-linux-gnu:qemu-aarch64:/usr/aarch64-linux-gnu" \
            "armv7-unknown-linux-gnueabihf:qemu-arm:/usr/arm-linux-gnueabihf"; do
  IFS=: read -r target qemu sysroot <<< "$spec"
  cargo build --quiet --release -p orient-tools --bin precision_cost --target "$target"
  bin="target/$target/release/precision_cost"
  for precision in f64 f32; do
    count() {
      "$qemu" -L "$sysroot" -singlestep -d exec,nochain -D "$work/log" "$bin" "$precision" "$1" > /dev/null
      grep -c '^Trace' "$work/log"
    }
    base=$(count 0)
    total=$(count "$n")
    echo "$target $precision: $(( (total - base) / n )) instructions per update"
  done
done
