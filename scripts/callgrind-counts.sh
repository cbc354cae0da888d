#!/usr/bin/env bash
# Instructions per update of every kind through the Rust API (or, with `c`, the C ABI), counted by callgrind:
# (count for 1000 + N updates - count for 1000 updates) / N, so start-up, reading the
# recording and printing cancel out. Unlike times, these do not move with machine load,
# so a change in them is a change in the code. Needs valgrind (scripts/setup-debian.sh).
#   scripts/callgrind-counts.sh [c]     (c: through orient_filter_update, the C ABI)
set -euo pipefail
cd "$(dirname "$0")/.."
N=${N:-5000}
via=${1:-}
cargo build --release --quiet -p orient-tools --bin bench
bin=target/release/bench
# The baseline (SSE2) code: valgrind 3.19 cannot decode every AVX instruction of the
# path a CPU with AVX takes (src/isa.rs).
count() {
  ORIENT_ISA=baseline valgrind --tool=callgrind --callgrind-out-file=/dev/null "$bin" --count "$1" "$2" "$3" $via 2>&1 \
    | sed -n 's/.*Collected : \([0-9]*\).*/\1/p'
}
printf '%-14s %-5s %12s\n' kind mode instr/update
for kind in madgwick mahony complementary ekf gmvdk robust; do
  for mode in imu marg; do
    a=$(count "$kind" "$mode" 1000)
    b=$(count "$kind" "$mode" $((1000 + N)))
    printf '%-14s %-5s %12.1f\n' "$kind" "$mode" "$(echo "($b - $a) / $N" | bc -l)"
  done
done
