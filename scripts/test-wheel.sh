#!/usr/bin/env bash
# Installs one orient-imu wheel into a fresh virtual environment with the pinned test
# requirements (bindings/python/requirements-test.txt) and runs tests/python with pytest
# from inside tests/python, so that only the installed wheel can be imported as `orient`.
#   scripts/test-wheel.sh WHEEL [REPLAY_TOOL] [PYTEST_ARGS...]
# (REPLAY_TOOL: the replay binary the BROAD test compares with; default target/debug/replay.)
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
wheel=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
replay="${2:-$root/target/debug/replay}"
shift $(($# < 2 ? $# : 2))
venv=$(mktemp -d "${TMPDIR:-/tmp}/orient-venv.XXXXXX")
trap 'rm -rf "$venv"' EXIT
python3 -m venv "$venv"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check -r bindings/python/requirements-test.txt
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check --no-deps "$wheel"
# pytest exits 5 when it collects no test: that fails here like any error.
status=0
(cd tests/python && ORIENT_REPLAY="$replay" "$venv/bin/python" -m pytest -q -p no:cacheprovider "$@" .) || status=$?
if [ "$status" = 5 ]; then echo "pytest collected no tests" >&2; fi
exit "$status"
