#!/usr/bin/env bash
# Every test, one `step` a line: setup, formatting, lints, the API documentation's links,
# the generated header and the exported symbols, the C# P/Invoke layer generated from the
# header, the ABI against its baseline, then cargo test: Rust unit and integration tests,
# doc tests, the C test program against the .so and the .a, the C++ wrapper (with and
# without exceptions), the C# binding under Mono and the Unity scripts against a stub, the
# examples in every language, the install layout with CMake and pkg-config consumers,
# golden vectors, and the BROAD recordings in ../shared/data; the Python package's sdist
# built into a wheel and tested with pytest in a fresh venv; the Conan recipe (conan
# create with its CMake consumer); Miri on the unsafe FFI code; the fuzz
# target's regression inputs and a short fuzz run; then, for aarch64 and armv7 under
# qemu-user, what can differ on a board (golden vectors bit for bit, the ABI's behaviour,
# the unit tests; scripts/test-cross.sh says what stays native and why); then the release
# for every platform, built with CI's lighter profile and checked: exports, glibc floor,
# Unity .meta files, the C ABI test under qemu and Wine, CMake and pkg-config, the C#
# tests under Mono full AOT (scripts/test-release.sh).
#
# Each step prints its wall time, and a table of them closes the run (also when a step
# fails), so the next slow step shows itself. Steps share one target directory: cargo
# test's `test` profile builds the tools too (the replay binary the Python and replay
# tests use); the release library is built once, by the header check, and reused by the
# ABI check, the wheel and the README's build lines.
set -euo pipefail
cd "$(dirname "$0")/.."

# step NAME -- COMMAND...: runs COMMAND (a program, not a shell function, so that its
# own `set -e` holds), prints its wall time, and records it for the closing table.
step_names=() step_times=() step_states=()
run_start=$EPOCHREALTIME
seconds_since() { awk -v a="$1" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.1f", b - a }'; }
step() {
  local name=$1 start status=0
  shift
  [ "${1:-}" = -- ] && shift
  echo "== $name: $*"
  start=$EPOCHREALTIME
  "$@" || status=$?
  step_names+=("$name") step_times+=("$(seconds_since "$start")")
  step_states+=("$([ "$status" = 0 ] && echo ok || echo "FAILED ($status)")")
  echo "-- $name: ${step_times[-1]} s, ${step_states[-1]}"
  return "$status"
}
step_table() {
  local i failed=0
  echo "== step times (wall, s; load average at the end: $(cut -d' ' -f1-3 /proc/loadavg))"
  for i in "${!step_names[@]}"; do
    printf '%8s  %-14s %s\n' "${step_times[$i]}" "${step_names[$i]}" "${step_states[$i]}"
    [ "${step_states[$i]}" = ok ] || failed=$((failed + 1))
  done
  printf '%8s  %s\n' "$(seconds_since "$run_start")" "in all"
  echo "steps: $((${#step_names[@]} - failed)) passed, $failed failed"
}
trap step_table EXIT

step setup -- scripts/setup-debian.sh --cross
export PATH="$HOME/.cargo/bin:$PATH"
step format -- cargo fmt --all -- --check
step clippy -- cargo clippy --workspace --all-targets --quiet -- -D warnings
# The library's API documentation, links included.
step rustdoc -- env RUSTDOCFLAGS="-D warnings" cargo doc -p orient --no-deps --quiet
step header -- scripts/check-header.sh
step csharp -- scripts/check-csharp.sh
step python-native -- scripts/check-python-native.sh
step abi -- scripts/check-abi.sh
# The library and the tools crate: every test, the slow sweeps (the day-long runs, the
# BROAD recordings, the recovery and property sweeps) run here and only here.
step test -- cargo test
step python -- scripts/test-python.sh
step conan -- scripts/test-conan.sh
# Miri: the unit tests of the modules that hold unsafe code (scripts/miri.sh says which).
step miri -- scripts/miri.sh
# Every input in fuzz/regressions, then a short deterministic run (FUZZ_SEED, default 1;
# the same 4000 executions on any machine; scripts/fuzz.sh RUNS for more).
step fuzz -- scripts/fuzz.sh 4000
step qemu-aarch64 -- scripts/test-cross.sh aarch64
step qemu-armv7 -- scripts/test-cross.sh armv7
step release -- scripts/test-release.sh
