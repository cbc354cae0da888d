#!/usr/bin/env bash
# CI for the release: runs scripts/release.sh (--ci: the lighter profile unless
# --release is given), validates its output with scripts/check-dist.py, then uses the
# built files the way users would:
#   - Linux glibc builds: the C ABI test (tests/c/abi_test.c, golden vectors bit for bit)
#     linked by zig against glibc 2.17, once with liborient.so and once with liborient.a,
#     run natively (x86_64) or under qemu-user (aarch64, armv7)
#   - musl builds: the C ABI test linked fully static, run the same way
#   - Windows: the C ABI test linked by MinGW with the DLL (through liborient.dll.a and
#     through the MSVC-style orient.lib) and with the static library, run under Wine
#     (with tests/wine/bcryptprimitives.c standing in for the DLL Wine 8 lacks)
#   - CMake and pkg-config on the Linux x86_64 folder: find_package(orient 1) links both
#     targets, find_package(orient 2) and find_package(orient 0.1) fail; orient-static.pc
#     links the archive; MinGW CMake finds the DLL and its import library
#   - C#: the binding's tests under Mono full AOT (the nearest stand-in for IL2CPP)
#   - Python: the manylinux2014 wheels' tests, x86_64 natively, aarch64 under qemu
#   - 16 KB page alignment of the aarch64 and Android shared libraries, and of an Android
#     link with a stand-in for the NDK's clang (scripts/check-android-link.sh)
#   scripts/test-release.sh [--release | --no-build] [OUT]
# (--no-build tests what an earlier run left in OUT.)
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
mode=--ci build=1
if [ "${1:-}" = "--release" ]; then mode=""; shift; fi
if [ "${1:-}" = "--no-build" ]; then build=0; shift; fi
out="${1:-$root/target/release-ci/dist}"
export PATH="$HOME/.cargo/bin:$PATH"
[ -d "$HOME/.local/orient-tools/bin" ] && export PATH="$HOME/.local/orient-tools/bin:$PATH"

start=$SECONDS
if [ "$build" = 1 ]; then
  # shellcheck disable=SC2086
  scripts/release.sh $mode "$out"
  echo "release.sh $mode: $((SECONDS - start)) s"
fi
version=$(sed -n 's/^version = "\(.*\)"/\1/p' Cargo.toml | head -n 1)
rel="$out/orient-$version"
scripts/check-dist.py "$rel"

echo "== Python wheels: manylinux2014 x86_64 natively, aarch64 under qemu"
scripts/test-release-python.sh "$rel"
echo "== 16 KB pages: the aarch64 and Android shared libraries"
scripts/check-page-size.py $(ls "$rel"/lib/linux-aarch64/liborient.so.*.*.* "$rel"/lib/android-*/liborient.so 2>/dev/null)
scripts/check-android-link.sh

golden="$root/tests/golden/filters.golden"
work="$out/test"
rm -rf "$work"
mkdir -p "$work"
cflags=(-std=c99 -O1 -Wall -Wextra -Werror -pedantic -I"$rel/include")
zigcc() { python3 -m ziglang cc "$@"; }

# expect_pass WHAT CMD...: the program's last line must be "N passed, 0 failed".
expect_pass() {
  local what=$1
  shift
  local log="$work/$(echo "$what" | tr ' /' '__').log"
  if ! "$@" >"$log" 2>&1; then
    cat "$log" >&2
    echo "FAIL $what" >&2
    exit 1
  fi
  local last
  last=$(tail -n 1 "$log" | tr -d '\r')
  case "$last" in
    *" 0 failed") echo "ok   $what: $last" ;;
    *) cat "$log" >&2; echo "FAIL $what: $last" >&2; exit 1 ;;
  esac
}

runner() {
  case $1 in
    x86_64) ;;
    aarch64) echo "qemu-aarch64 -L /usr/aarch64-linux-gnu" ;;
    armv7) echo "qemu-arm -L /usr/arm-linux-gnueabihf" ;;
  esac
}

echo "== Linux: C ABI test against the glibc 2.17 builds"
for arch in x86_64 aarch64 armv7; do
  case $arch in
    armv7) zt=arm-linux-gnueabihf ;;
    *) zt=$arch-linux-gnu ;;
  esac
  lib="$rel/lib/linux-$arch"
  exe="$work/abi_test-$arch"
  zigcc -target "$zt.2.17" "${cflags[@]}" tests/c/abi_test.c -o "$exe-shared" -L"$lib" -lorient -lm
  # shellcheck disable=SC2046
  zigcc -target "$zt.2.17" "${cflags[@]}" tests/c/abi_test.c -o "$exe-static" "$lib/liborient.a" \
    $(sed -n 's/^Libs: [^ ]* //p' "$lib/pkgconfig/orient-static.pc")
  # shellcheck disable=SC2046
  expect_pass "linux-$arch shared (glibc 2.17 link)" env LD_LIBRARY_PATH="$lib" $(runner $arch) "$exe-shared" "$golden"
  # shellcheck disable=SC2046
  expect_pass "linux-$arch static (glibc 2.17 link)" $(runner $arch) "$exe-static" "$golden"
done

echo "== Linux musl: fully static C ABI test"
for d in "$rel"/lib/linux-*-musl; do
  p=$(basename "$d")
  arch=${p#linux-}
  arch=${arch%-musl}
  case $arch in
    armv7) zt=arm-linux-musleabihf ;;
    *) zt=$arch-linux-musl ;;
  esac
  exe="$work/abi_test-$p"
  # The test's calls with a freed handle run here too: the handle registry refuses them
  # without reading the freed memory, which musl's allocator unmaps.
  zigcc -target "$zt" -static "${cflags[@]}" tests/c/abi_test.c -o "$exe" "$d/liborient.a"
  if llvm-objdump -p "$exe" | grep -c NEEDED >/dev/null; then
    echo "FAIL $p: the program is not fully static" >&2
    exit 1
  fi
  # shellcheck disable=SC2046
  expect_pass "$p static" $(runner "$arch" | cut -d' ' -f1) "$exe" "$golden"
done

echo "== Windows: MinGW links the DLL and the static library; runs under Wine"
win="$rel/lib/windows-x86_64"
wdir="$work/windows"
mkdir -p "$wdir"
cc=x86_64-w64-mingw32-gcc
$cc "${cflags[@]}" tests/c/abi_test.c -o "$wdir/abi_test_dll.exe" -L"$win" -lorient
$cc "${cflags[@]}" tests/c/abi_test.c -o "$wdir/abi_test_lib.exe" "$win/orient.lib"
# shellcheck disable=SC2046
$cc "${cflags[@]}" tests/c/abi_test.c -o "$wdir/abi_test_static.exe" "$win/liborient.a" \
  $(sed -n 's/^Libs: [^ ]* //p' "$win/pkgconfig/orient-static.pc")
for exe in abi_test_dll abi_test_lib; do
  llvm-objdump -p "$wdir/$exe.exe" | grep -c "DLL Name: orient.dll" >/dev/null || { echo "FAIL $exe does not import orient.dll" >&2; exit 1; }
done
cp "$win/orient.dll" "$wdir/"
$cc -O2 -shared -o "$wdir/bcryptprimitives.dll" tests/wine/bcryptprimitives.c tests/wine/bcryptprimitives.def -ladvapi32
wine=$(command -v wine64 || echo /usr/lib/wine/wine64)
if [ -x "$wine" ]; then
  export WINEPREFIX="$root/target/wine-prefix" WINEDEBUG=-all WINEDLLOVERRIDES="bcryptprimitives=n"
  [ -d "$WINEPREFIX" ] || "$wine" wineboot --init >/dev/null 2>&1 || true
  for exe in abi_test_dll abi_test_lib abi_test_static; do
    expect_pass "windows-x86_64 $exe.exe under Wine" sh -c "cd '$wdir' && '$wine' ./$exe.exe '$golden'"
  done
else
  echo "FAIL wine64 not found (scripts/setup-debian.sh installs it)" >&2
  exit 1
fi

echo "== CMake and pkg-config on the release's linux-x86_64 folder"
lib="$rel/lib/linux-x86_64"
configure_consumer() { # BUILD_DIR REQUEST [extra cmake args]
  local b=$1 req=$2
  shift 2
  rm -rf "$b"
  cmake -S tests/cmake_consumer -B "$b" -DCMAKE_PREFIX_PATH="$lib" -DORIENT_REQUEST="$req" "$@" >"$b.log" 2>&1
}
configure_consumer "$work/cmake-1" 1
cmake --build "$work/cmake-1" >"$work/cmake-1-build.log" 2>&1 || { cat "$work/cmake-1-build.log"; exit 1; }
for exe in consumer_shared consumer_static consumer_cpp; do
  "$work/cmake-1/$exe" | grep -c "q = (" >/dev/null || { echo "FAIL cmake $exe" >&2; exit 1; }
done
readelf -d "$work/cmake-1/consumer_static" | grep -c liborient >/dev/null && { echo "FAIL consumer_static needs liborient.so" >&2; exit 1; }
for req in 2 0.1 1.99; do
  if configure_consumer "$work/cmake-$req" "$req"; then
    echo "FAIL find_package(orient $req) accepted ABI 1 version $(grep -o 'orient [0-9.]*' "$work/cmake-$req.log" | head -n 1)" >&2
    exit 1
  fi
done
echo "ok   find_package(orient 1) links orient::orient and orient::orient_static; 2, 0.1 and 1.99 are refused"
PKG_CONFIG_PATH="$lib/pkgconfig" pkg-config --libs orient-static | grep -c "liborient.a" >/dev/null || { echo "FAIL orient-static.pc" >&2; exit 1; }
# shellcheck disable=SC2046
cc tests/cmake_consumer/consumer.c -o "$work/pc_static" $(PKG_CONFIG_PATH="$lib/pkgconfig" pkg-config --cflags --libs orient-static)
readelf -d "$work/pc_static" | grep -c liborient >/dev/null && { echo "FAIL pkg-config static program needs liborient.so" >&2; exit 1; }
"$work/pc_static" | grep -c "q = (" >/dev/null
echo "ok   pkg-config --libs orient-static links the archive"

cat >"$work/mingw.cmake" <<'EOF'
set(CMAKE_SYSTEM_NAME Windows)
set(CMAKE_C_COMPILER x86_64-w64-mingw32-gcc)
set(CMAKE_CXX_COMPILER x86_64-w64-mingw32-g++)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE BOTH)
EOF
rm -rf "$work/cmake-mingw"
cmake -S tests/cmake_consumer -B "$work/cmake-mingw" -DCMAKE_TOOLCHAIN_FILE="$work/mingw.cmake" \
  -DCMAKE_PREFIX_PATH="$win" >"$work/cmake-mingw.log" 2>&1 || { cat "$work/cmake-mingw.log"; exit 1; }
cmake --build "$work/cmake-mingw" --target consumer_shared consumer_static >>"$work/cmake-mingw.log" 2>&1 ||
  { cat "$work/cmake-mingw.log"; exit 1; }
cp "$win/orient.dll" "$wdir/bcryptprimitives.dll" "$work/cmake-mingw/"
for exe in consumer_shared consumer_static; do
  (cd "$work/cmake-mingw" && "$wine" ./$exe.exe) | grep -c "q = (" >/dev/null || { echo "FAIL MinGW CMake $exe under Wine" >&2; exit 1; }
done
echo "ok   MinGW CMake: orient::orient (DLL + import library) and orient::orient_static run under Wine"

echo "== README: the C build lines as written; CMake add_subdirectory of the repository"
# The lines after "After `cargo build --release`" in README.md, run as a user would, from
# the checkout's root (check-header.sh built the release library), with a complete
# program as app.c; app.c, app and out/ are removed afterwards.
mapfile -t lines < <(sed -n '/^After `cargo build --release`/,/^(`/p' README.md | grep -o '`[^`]*app\.c[^`]*`' | tr -d '`')
[ "${#lines[@]}" = 2 ] || { echo "FAIL README: expected 2 C build lines, found ${#lines[@]}" >&2; exit 1; }
[ -f target/release/liborient.a ] || cargo build --release -p orient --lib --quiet
[ ! -e app.c ] && [ ! -e app ] && [ ! -e out ] || { echo "FAIL app.c, app or out/ already in $root" >&2; exit 1; }
trap 'rm -rf "$root/app.c" "$root/app" "$root/out"' EXIT
cp tests/cmake_consumer/consumer.c app.c
for line in "${lines[@]}"; do
  rm -f app
  sh -c "$line" >"$work/readme-build.log" 2>&1 || { cat "$work/readme-build.log"; echo "FAIL README line: $line" >&2; exit 1; }
  (cd /tmp && "$root/app") | grep -c "q = (" >/dev/null || { echo "FAIL README line builds a program that does not run: $line" >&2; exit 1; }
  echo "ok   README: $line"
done
rm -rf "$root/app.c" "$root/app" "$root/out"
rm -rf "$work/cmake-subdir"
# cargo's own target directory: the release build check-header.sh made is reused.
cmake -S tests/cmake_consumer -B "$work/cmake-subdir" -DORIENT_SOURCE_DIR="$root" \
  -DORIENT_CARGO_TARGET_DIR="$root/target" >"$work/cmake-subdir.log" 2>&1 &&
  cmake --build "$work/cmake-subdir" >>"$work/cmake-subdir.log" 2>&1 || { cat "$work/cmake-subdir.log"; exit 1; }
for exe in consumer_shared consumer_static consumer_cpp; do
  "$work/cmake-subdir/$exe" | grep -c "q = (" >/dev/null || { echo "FAIL add_subdirectory $exe" >&2; exit 1; }
done
echo "ok   add_subdirectory: the top-level CMakeLists.txt builds with cargo; all three consumers run"

echo "== C#: the binding's tests under Mono full AOT"
aot="$root/target/mono-aot"
mkdir -p "$aot"
for a in mscorlib System System.Core; do
  if [ ! -f "$aot/$a.dll.so" ] || [ "/usr/lib/mono/4.5/$a.dll" -nt "$aot/$a.dll.so" ]; then
    cp "/usr/lib/mono/4.5/$a.dll" "$aot/"
    MONO_PATH="$aot" mono --aot=full "$aot/$a.dll" >"$work/aot-$a.log" 2>&1 || { cat "$work/aot-$a.log"; exit 1; }
  fi
done
cs="$work/csharp"
mkdir -p "$cs"
cp "$lib/liborient.so.1".* "$cs/liborient.so"
mcs -unsafe -warnaserror -nologo -out:"$cs/OrientTests.exe" bindings/csharp/Orient.Native.cs bindings/csharp/Orient.cs tests/csharp/OrientTests.cs
MONO_PATH="$aot" mono --aot=full "$cs/OrientTests.exe" >"$work/aot-tests.log" 2>&1 || { cat "$work/aot-tests.log"; exit 1; }
expect_pass "C# tests under mono --full-aot" env MONO_PATH="$aot" LD_LIBRARY_PATH="$cs" mono --full-aot "$cs/OrientTests.exe" "$golden"
echo "release tests: $((SECONDS - start)) s in all"
