#!/usr/bin/env bash
# The Python release: the sdist and one py3-none wheel per platform, from a release's
# libraries (scripts/release.sh calls this once they are built), through the same
# backend as `pip install .` (pyproject.toml, scikit-build-core) with
# ORIENT_PYTHON_LIBRARY naming the library to bundle and the platform tag given:
#   linux-x86_64, linux-aarch64 (glibc 2.17 builds)  manylinux2014: built as linux_<arch>,
#       then `auditwheel repair --plat auto` reads what the library needs (symbol
#       versions, libraries), tags the wheel with the oldest manylinux policy that allows
#       it, and this script requires that to be manylinux2014 (glibc 2.17). (auto: on an
#       x86_64 host auditwheel offers only x86_64 names for --plat.)
#   macos-universal    macosx_<minos>_universal2, minos the highest of the slices' own
#   windows-x86_64     win_amd64
#   scripts/release-wheels.sh REL OUT
set -euo pipefail
cd "$(dirname "$0")/.."
rel=$1 out=$2
tools=$(scripts/python-tools.sh)
llvm="$(rustc --print sysroot)/lib/rustlib/$(rustc -vV | sed -n 's/^host: //p')/bin"
work=$(mktemp -d "${TMPDIR:-/tmp}/orient-wheels.XXXXXX")
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"
rm -f "$out"/orient_imu-*
# Byte-identical wheels from the same commit: file times from the commit's time.
export SOURCE_DATE_EPOCH="${SOURCE_DATE_EPOCH:-$(git log -1 --format=%ct 2>/dev/null || echo 315532800)}"

"$tools/pyproject-build" --sdist --no-isolation --outdir "$out" . >"$work/sdist.log" 2>&1 || { cat "$work/sdist.log"; exit 1; }

# wheel LIBRARY TAG DIR: the package with LIBRARY bundled, tagged py3-none-TAG, into DIR.
wheel() {
  "$tools/python" -m pip wheel --quiet --disable-pip-version-check --no-deps --no-build-isolation \
    --wheel-dir "$3" . -C build-dir="$work/build-$2" \
    -C cmake.define.ORIENT_PYTHON_LIBRARY="$1" -C wheel.tags="py3-none-$2" >"$work/$2.log" 2>&1 ||
    { cat "$work/$2.log"; exit 1; }
}

for arch in x86_64 aarch64; do
  lib=$(ls "$rel/lib/linux-$arch"/liborient.so.*.*.*)
  wheel "$lib" "linux_$arch" "$work/linux"
  PATH="$tools:$PATH" "$tools/auditwheel" repair --plat auto --wheel-dir "$work/repaired" \
    "$work/linux"/orient_imu-*-py3-none-linux_"$arch".whl >"$work/auditwheel-$arch.log" 2>&1 ||
    { cat "$work/auditwheel-$arch.log"; exit 1; }
  w=$(ls "$work/repaired"/orient_imu-*-py3-none-*"$arch".whl)
  case $(basename "$w") in
    *-py3-none-manylinux2014_"$arch".manylinux_2_17_"$arch".whl) mv "$w" "$out/" ;;
    *) cat "$work/auditwheel-$arch.log"; echo "FAIL auditwheel tags $(basename "$w"), not manylinux2014" >&2; exit 1 ;;
  esac
done

dylib="$rel/lib/macos-universal/liborient.dylib"
# The wheel's macOS version: the highest minimum of the two slices (LC_BUILD_VERSION).
minos=$(for a in arm64 x86_64; do
  "$llvm/llvm-objdump" --macho --private-headers --arch=$a "$dylib" | awk '$1 == "minos" { print $2; exit }'
done | sort -V | tail -n 1)
wheel "$dylib" "macosx_${minos/./_}_universal2" "$out"
wheel "$rel/lib/windows-x86_64/orient.dll" win_amd64 "$out"
ls -l "$out"
