#!/usr/bin/env bash
# Instructions per update of every kind through the Rust API (or, with `c`, the C ABI), and
# of the anchors (ahrs-rs Madgwick and Mahony f64, vqf-rs) in the same loop, each update
# followed by one orientation read, counted by callgrind:
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
per_update() {
  local a b
  a=$(count "$1" "$2" 1000)
  b=$(count "$1" "$2" $((1000 + N)))
  echo "($b - $a) / $N" | bc -l
}
printf '%-14s %-5s %12s   %s\n' kind mode instr/update 'anchor (instr/update, orient / anchor)'
for kind in madgwick mahony complementary ekf gmvdk robust; do
  case $kind in
    madgwick) anchor=ahrs-madgwick ;;
    mahony) anchor=ahrs-mahony ;;
    robust) anchor=vqf ;;
    *) anchor= ;;
  esac
  for mode in imu marg; do
    o=$(per_update "$kind" "$mode")
    line=$(printf '%-14s %-5s %12.1f' "$kind" "$mode" "$o")
    if [ -n "$anchor" ] && [ -z "$via" ]; then
      x=$(per_update "$anchor" "$mode")
      line="$line   $(printf '%s %.1f, %.2f' "$anchor" "$x" "$(echo "$o / $x" | bc -l)")"
    fi
    echo "$line"
  done
done
# One frame of the bench's 20-sensor Madgwick MARG rig through the C ABI, per frame:
# orient_filters_update with quaternions out, and 20 orient_filter_update calls each with
# orient_filter_quaternion (bench --count-frame).
if [ -z "$via" ]; then
  frame() {
    ORIENT_ISA=baseline valgrind --tool=callgrind --callgrind-out-file=/dev/null "$bin" --count-frame "$1" "$2" 2>&1 \
      | sed -n 's/.*Collected : \([0-9]*\).*/\1/p'
  }
  for how in multi single; do
    a=$(frame "$how" 200)
    b=$(frame "$how" 1200)
    printf '%-14s %-5s %12.1f   (20-sensor frame, per frame)\n' "frame-$how" marg "$(echo "($b - $a) / 1000" | bc -l)"
  done
fi
# A joint beside its two filters (orient::joints, Rust API): two robust IMU filters per
# row, with and without one joint updated after them and its child segment read
# (bench --count-joints), per row.
if [ -z "$via" ]; then
  joints() {
    ORIENT_ISA=baseline valgrind --tool=callgrind --callgrind-out-file=/dev/null "$bin" --count-joints "$1" "$2" 2>&1 \
      | sed -n 's/.*Collected : \([0-9]*\).*/\1/p'
  }
  per_row() { echo "($(joints "$1" 1200) - $(joints "$1" 200)) / 1000" | bc -l; }
  two=$(per_row filters)
  printf '%-14s %-5s %12.1f   (two robust filters, per row)\n' "rig-2-filters" imu "$two"
  for how in hinge 2dof; do
    j=$(per_row "$how")
    printf '%-14s %-5s %12.1f   (one joint beside them, per row; %.2f x one filter)\n' "joint-$how" imu \
      "$(echo "$j - $two" | bc -l)" "$(echo "($j - $two) * 2 / $two" | bc -l)"
  done
fi
