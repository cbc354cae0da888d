#!/usr/bin/env bash
# Tests the manylinux aarch64 wheel on aarch64: Debian's own CPython 3.11 for arm64 runs
# under qemu-user, in a fresh virtual environment holding the wheel and the pinned test
# requirements' aarch64 wheels (matplotlib left out: the plot test is skipped), and runs
# tests/python from inside tests/python.
#   scripts/test-wheel-qemu.sh WHEEL [REPLAY_TOOL]
# The interpreter comes from Debian's arm64 packages, fetched with apt-get into
# target/qemu-python (a package list and cache of its own, so the machine's apt setup and
# architectures are left alone) and unpacked there, not installed.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
wheel=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
replay="${2:-$root/target/debug/replay}"
base="$root/target/qemu-python"
sysroot="$base/root"
if [ ! -x "$sysroot/usr/bin/python3.11" ]; then
  rm -rf "$base"
  mkdir -p "$base/lists/partial" "$base/cache/archives/partial" "$base/debs" "$sysroot"
  touch "$base/status"
  apt_opts=(-o APT::Architecture=arm64 -o APT::Architectures::=arm64 -o Dir::State::Lists="$base/lists"
    -o Dir::Cache="$base/cache" -o Dir::State::status="$base/status" -o Debug::NoLocking=1)
  apt-get "${apt_opts[@]}" update -qq
  (cd "$base/debs" && apt-get "${apt_opts[@]}" download -qq python3.11-minimal libpython3.11-minimal \
    libpython3.11-stdlib libffi8 zlib1g libexpat1 libbz2-1.0 liblzma5 2>&1 | grep -v '^W: Download is performed unsandboxed' || true)
  for d in "$base"/debs/*.deb; do dpkg -x "$d" "$sysroot"; done
fi
qemu=(qemu-aarch64 -L /usr/aarch64-linux-gnu
  -E LD_LIBRARY_PATH="$sysroot/usr/lib/aarch64-linux-gnu:$sysroot/lib/aarch64-linux-gnu")
venv=$(mktemp -d "${TMPDIR:-/tmp}/orient-venv-aarch64.XXXXXX")
trap 'rm -rf "$venv"' EXIT
"${qemu[@]}" "$sysroot/usr/bin/python3.11" -m venv --without-pip "$venv"
grep -vE '^(#|$|matplotlib|contourpy|cycler|fonttools|kiwisolver|pillow|pyparsing|python-dateutil|tzdata)' \
  bindings/python/requirements-test.txt >"$venv/requirements.txt"
python3 -m pip install --quiet --disable-pip-version-check --root-user-action=ignore --target "$venv/lib/python3.11/site-packages" \
  --platform manylinux2014_aarch64 --only-binary=:all: --python-version 3.11 --implementation cp \
  -r "$venv/requirements.txt" "$wheel"
"${qemu[@]}" "$venv/bin/python" -c 'import platform, orient; print("aarch64 python", platform.python_version(), platform.machine(), "orient", orient.version(), orient.__file__)'
status=0
(cd tests/python && ORIENT_REPLAY="$replay" ORIENT_HOST_PYTHON="$(command -v python3)" "${qemu[@]}" "$venv/bin/python" -m pytest -q -p no:cacheprovider .) || status=$?
if [ "$status" = 5 ]; then echo "pytest collected no tests" >&2; fi
exit "$status"
