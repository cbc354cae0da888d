#!/usr/bin/env bash
# The Python package (bindings/python): builds the wheel from the release library,
# installs it into a fresh virtual environment with the pinned test requirements, and
# runs tests/python with pytest (golden vectors, every status, a BROAD trial against the
# replay tool, the plot). Prints how long the wheel build and the whole run took.
#   scripts/test-python.sh [WHEEL_DIR]     (default target/wheels)
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH="$HOME/.cargo/bin:$PATH"
elapsed() { awk -v a="$1" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.1f", b - a }'; }
start=$EPOCHREALTIME
out="${1:-target/wheels}"
wheel_start=$EPOCHREALTIME
cargo build --release -p orient --lib --quiet
rm -f "$out"/orient_imu-*.whl
wheel=$(python3 bindings/python/build_wheel.py --lib target/release/liborient.so --out "$out")
echo "wheel: $wheel ($(du -k "$wheel" | cut -f1) KiB, $(elapsed "$wheel_start") s with the library build)"
# The BROAD test compares with the replay tool (the tools crate), built with cargo test's
# profile: a no-op after `cargo test`, which built it, and no second build of every
# dependency at another optimisation level.
cargo build --quiet --profile test -p orient-tools --bin replay
replay=target/debug/replay
# A fresh environment outside the source tree, removed afterwards.
venv=$(mktemp -d "${TMPDIR:-/tmp}/orient-venv.XXXXXX")
trap 'rm -rf "$venv"' EXIT
python3 -m venv "$venv"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check -r bindings/python/requirements-test.txt
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check --no-deps "$wheel"
# Run from tests/python so that nothing but the installed wheel can be imported as
# `orient`. pytest exits 5 when it collects no test: that fails here like any error.
status=0
(cd tests/python && ORIENT_REPLAY="$PWD/../../$replay" "$venv/bin/python" -m pytest -q -p no:cacheprovider .) ||
  status=$?
if [ "$status" = 5 ]; then echo "pytest collected no tests" >&2; fi
echo "python: $(elapsed "$start") s in all"
exit "$status"
