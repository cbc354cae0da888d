#!/usr/bin/env bash
# Guest instructions per update of every kind on the board targets (aarch64, armv7),
# and on an x86-64 host also of the host build's two x86-64 copies, counted under
# qemu-user by a TCG plugin (scripts/qemu/insn_count.c, built here with
# the host's cc): (count for B + N updates - count for B updates) / N, through the Rust
# API (tools/src/bin/bench.rs --count, each update followed by one orientation read, as
# for the anchors counted beside the kinds), so start-up, reading the recording and printing
# cancel out. The plugin's totals equal qemu's single-step log (one line per executed
# instruction, scripts/instruction-counts.sh's method) to the instruction. Counts, not
# times: emulation says nothing about a board's clock, but on in-order cores
# (Cortex-A7/A53) instruction count is close to time.
#
# x86-64: callgrind (scripts/callgrind-counts.sh) counts only the baseline (SSE2) code,
# since valgrind 3.19 cannot decode the AVX copy that the EKF and GMVDK take on a CPU with
# AVX (src/isa.rs). qemu-x86_64 with `-cpu max` (AVX, TCG) runs the host's own release
# build and counts both: `avx`, the code such a CPU runs, and `sse2` (ORIENT_ISA=baseline),
# which repeats callgrind's count through a second instrument.
#   scripts/guest-instruction-counts.sh [N]      (default 10000; needs setup-debian.sh --cross)
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH="$HOME/.cargo/bin:$PATH"
n="${1:-10000}"
base=200
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cc -shared -fPIC -O2 -o "$work/insn_count.so" scripts/qemu/insn_count.c
printf '%-30s %-14s %-5s %12s\n' target kind mode instr/update
specs=("aarch64-unknown-linux-gnu:qemu-aarch64:/usr/aarch64-linux-gnu"
       "armv7-unknown-linux-gnueabihf:qemu-arm:/usr/arm-linux-gnueabihf")
if [ "$(uname -m)" = x86_64 ] && command -v qemu-x86_64 >/dev/null; then
  specs+=("x86_64-avx:qemu-x86_64:" "x86_64-sse2:qemu-x86_64:")
fi
for spec in "${specs[@]}"; do
  IFS=: read -r target qemu sysroot <<< "$spec"
  isa=
  case $target in
    x86_64-*)
      cargo build --quiet --release -p orient-tools --bin bench
      bin=target/release/bench
      args=(-cpu max)
      [ "$target" = x86_64-sse2 ] && isa=baseline
      ;;
    *)
      cargo build --quiet --release -p orient-tools --bin bench --target "$target"
      bin="target/$target/release/bench"
      args=(-L "$sysroot")
      ;;
  esac
  run() {
    ORIENT_ISA=$isa "$qemu" "${args[@]}" -plugin "$work/insn_count.so" "$bin" "$@" 2>&1 >/dev/null \
      | sed -n 's/^guest instructions: //p'
  }
  count() { run --count "$1" "$2" "$3"; }
  # The kinds, then the anchors in the same loop (ahrs-rs Madgwick and Mahony f64, vqf-rs).
  for kind in madgwick mahony complementary ekf gmvdk robust ahrs-madgwick ahrs-mahony vqf; do
    for mode in imu marg; do
      a=$(count "$kind" "$mode" "$base")
      b=$(count "$kind" "$mode" $((base + n)))
      printf '%-30s %-14s %-5s %12.1f\n' "$target" "$kind" "$mode" "$(echo "($b - $a) / $n" | bc -l)"
    done
  done
  # The bench's 20-sensor Madgwick MARG rig, per frame (bench --count-frame): one
  # orient_filters_update with quaternions out, or 20 single calls each with its read.
  for how in multi single; do
    a=$(run --count-frame "$how" 20)
    b=$(run --count-frame "$how" 520)
    printf '%-30s %-14s %-5s %12.1f   (per frame)\n' "$target" "frame-$how" marg "$(echo "($b - $a) / 500" | bc -l)"
  done
done
