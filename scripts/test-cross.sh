#!/usr/bin/env bash
# The tests for a Linux board target under qemu-user that can tell the board from the
# build machine: the golden vectors bit for bit (Rust, C and C++), the ABI's behaviour
# from C and C++ programs built by the target's compiler (tests/common/native.rs starts
# them through qemu), pointer width and layout (handles, snapshot blobs, allocation,
# threads), the unit tests, and the quick behavioural tests.
#   scripts/test-cross.sh aarch64|armv7 [--all]
#
# Native only (`cargo test` in scripts/test-all.sh runs them, at ten times qemu's speed):
# the sweeps whose every number follows from the arithmetic that the golden vectors pin
# bit for bit on the board (one tests/golden file for every platform: libm for the
# transcendentals, no FMA contraction). In CI they took 560 of the 610 s of test time in
# the two qemu runs:
#   BROAD recordings   broad, broad_calibration, broad_uncertainty, offline
#   long simulations   long_run (a simulated day; it skipped itself under qemu already),
#                      sensor_model_usable, paper_claims, robust_sim, robust_uncertainty
#   property and       accepted_input, recovery, ekf_recovery, gaps, calibrator_attack
#   recovery sweeps
#   the replay tool    replay_cli (file and CSV handling in the tools crate; a debug
#                      build of the tools for the board besides)
# A new test file runs here too unless it is added to this list. --all runs everything.
set -euo pipefail
cd "$(dirname "$0")/.."
case "${1:-}" in
  aarch64) target=aarch64-unknown-linux-gnu ;;
  armv7) target=armv7-unknown-linux-gnueabihf ;;
  *) echo "usage: $0 aarch64|armv7 [--all]" >&2; exit 2 ;;
esac
if [ "${2:-}" = --all ]; then
  exec cargo test --target "$target"
fi
native_only=" accepted_input broad broad_calibration broad_uncertainty offline long_run
  sensor_model_usable paper_claims robust_sim robust_uncertainty recovery ekf_recovery gaps
  calibrator_attack replay_cli "
tests=(--lib)
for f in tests/*.rs; do
  name=$(basename "$f" .rs)
  case "$native_only" in *[[:space:]]"$name"[[:space:]]*) ;; *) tests+=(--test "$name") ;; esac
done
# Naming test files leaves the examples unbuilt; tests/examples.rs runs the quickstart
# built for the board.
cargo build --quiet --target "$target" -p orient --examples
cargo test --target "$target" -p orient "${tests[@]}"
# The tools crate: its unit tests and the bench floors (tools/tests/floor.rs), which
# must compute the cores' numbers on the board too. tools/tests/rig.rs starts the replay
# binary itself (not through the emulator): native only.
cargo test --target "$target" -p orient-tools --lib --test floor
