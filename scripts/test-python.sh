#!/usr/bin/env bash
# The Python package as a user gets it: builds the sdist with the standard backend
# (pyproject.toml, scikit-build-core), builds the wheel from that sdist (so a file the
# sdist leaves out fails here), checks the wheel's name and contents, installs it into a
# fresh virtual environment with the pinned test requirements, and runs tests/python with
# pytest from outside the source tree (golden vectors, every status, a BROAD trial
# against the replay tool, the plot). Prints how long each part took.
#   scripts/test-python.sh [OUT]     (default target/wheels)
# The library is compiled with CI's lighter profile (opt-level 1, no LTO; Rust never
# fuses multiply-add, so the results are the same bits) in target/ci-light (shared with scripts/test-conan.sh), which later
# runs reuse for everything but orient itself.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
export PATH="$HOME/.cargo/bin:$PATH"
elapsed() { awk -v a="$1" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.1f", b - a }'; }
start=$EPOCHREALTIME
out="${1:-target/wheels}"
mkdir -p "$out"
out=$(cd "$out" && pwd)
version=$(sed -n 's/^version = "\(.*\)"/\1/p' Cargo.toml | head -n 1)
work=$(mktemp -d "${TMPDIR:-/tmp}/orient-python.XXXXXX")
trap 'rm -rf "$work"' EXIT
pip=(python3 -m pip --disable-pip-version-check)

tools=$(scripts/python-tools.sh)

step=$EPOCHREALTIME
rm -f "$out"/orient_imu-*
"$tools/pyproject-build" --sdist --outdir "$out" . >"$work/sdist.log" 2>&1 || { cat "$work/sdist.log"; exit 1; }
sdist="$out/orient_imu-$version.tar.gz"
[ -f "$sdist" ] || { echo "FAIL no $sdist" >&2; exit 1; }
echo "sdist: $sdist ($(du -k "$sdist" | cut -f1) KiB, $(tar tzf "$sdist" | wc -l) files, $(elapsed "$step") s)"

# The wheel from the unpacked sdist. Its files carry the sdist's fixed timestamps: touch
# them, or cargo would take an older build in the shared target directory as fresh.
step=$EPOCHREALTIME
tar xzf "$sdist" -C "$work"
find "$work/orient_imu-$version" -type f -exec touch {} +
CARGO_PROFILE_RELEASE_OPT_LEVEL=1 CARGO_PROFILE_RELEASE_LTO=off CARGO_PROFILE_RELEASE_CODEGEN_UNITS=16 \
  "${pip[@]}" wheel --no-deps --wheel-dir "$out" "$work/orient_imu-$version" \
  -C cmake.define.ORIENT_CARGO_TARGET_DIR="$root/target/ci-light" >"$work/wheel.log" 2>&1 ||
  { cat "$work/wheel.log"; exit 1; }
wheel=$(ls "$out"/orient_imu-"$version"-py3-none-*.whl)
echo "wheel from the sdist: $(basename "$wheel") ($(du -k "$wheel" | cut -f1) KiB, $(elapsed "$step") s)"
# Every file of bindings/python/orient is in the wheel, beside the library.
python3 - "$wheel" bindings/python/orient <<'EOF'
import sys, zipfile
from pathlib import Path
names = set(zipfile.ZipFile(sys.argv[1]).namelist())
want = {f"orient/{p.name}" for p in Path(sys.argv[2]).iterdir() if p.is_file() and p.suffix != ".pyc"}
want.add("orient/liborient.so")
missing = sorted(want - names)
if missing:
    sys.exit(f"FAIL the wheel lacks {missing}")
EOF

# The BROAD test compares with the replay tool (the tools crate), built with cargo test's
# profile: a no-op after `cargo test`, which built it, and no second build of every
# dependency at another optimisation level.
cargo build --quiet --profile test -p orient-tools --bin replay
step=$EPOCHREALTIME
scripts/test-wheel.sh "$wheel" "$root/target/debug/replay"
echo "python: tests $(elapsed "$step") s, $(elapsed "$start") s in all"
