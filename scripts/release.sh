#!/usr/bin/env bash
# Builds orient for every platform its users run, from one Debian machine, and
# assembles the release:
#   scripts/release.sh [--ci] [OUT]          (OUT defaults to dist)
#
# OUT/orient-VERSION/
#   include/orient.h  bindings/cpp/orient.hpp  LICENSE-MIT  LICENSE-APACHE  CHANGELOG.md
#   README.md  SHA256SUMS (every other file, archives included)
#   lib/<platform>/   the libraries, cmake/ (CMake package) and pkgconfig/
#   unity/com.orient.filters/   the Unity package (scripts/package-unity.sh)
#   python/   orient_imu-VERSION.tar.gz (sdist) and py3-none wheels: manylinux2014 x86_64
#       and aarch64, macOS universal2, win_amd64 (scripts/release-wheels.sh)
#   archives/orient-VERSION-<platform>.tar.gz (.zip for Windows), com.orient.filters-VERSION.tgz
#
# Platforms (platform folder: what, how):
#   linux-x86_64, linux-aarch64, linux-armv7   liborient.so.1 and liborient.a, linked by
#       cargo-zigbuild against glibc 2.17 (target suffix .2.17): runs on glibc >= 2.17
#   linux-x86_64-musl, linux-aarch64-musl, linux-armv7-musl   liborient.a for fully
#       static musl programs (LLVM's libunwind included); rustup serves no std for
#       armv7-unknown-linux-musleabihf (404), so that one is built with nightly's
#       -Zbuild-std from rust-src, with libunwind compiled by zig
#   windows-x86_64   orient.dll, orient.lib (MSVC import library), liborient.dll.a
#       (MinGW import library), liborient.a (MinGW static), built with Debian's mingw-w64
#   macos-universal  liborient.dylib (arm64 + x86_64, install name @rpath/liborient.dylib),
#       linked by rust-lld against zig's libSystem stub (zig's own Mach-O linker ignores
#       the export list, so it would export every Rust symbol)
#   ios-arm64, android-arm64-v8a, android-armeabi-v7a   liborient.a (no linker needed);
#       with an Android NDK (ANDROID_NDK_HOME) also liborient.so, 16 KB page aligned
#
# --ci builds with a lighter profile (opt-level 1, no LTO, 16 codegen units) into
# target/release-ci; the layout and checks are the same. scripts/check-dist.py
# validates the result; scripts/test-release.sh runs it all in CI.
# Tools: scripts/setup-debian.sh --release installs them.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD

ci=0
if [ "${1:-}" = "--ci" ]; then ci=1; shift; fi
out="${1:-dist}"
mkdir -p "$out"
out=$(cd "$out" && pwd)

version=$(sed -n 's/^version = "\(.*\)"/\1/p' Cargo.toml | head -n 1)
abi=$(sed -n 's/^#define ORIENT_ABI_VERSION \([0-9]*\)$/\1/p' include/orient.h)
full="$abi.${version#*.}"
rel="$out/orient-$version"
export PATH="$HOME/.cargo/bin:$PATH"
[ -d "$HOME/.local/orient-tools/bin" ] && export PATH="$HOME/.local/orient-tools/bin:$PATH"
host=$(rustc -vV | sed -n 's/^host: //p')
llvm="$(rustc --print sysroot)/lib/rustlib/$host/bin"
[ -x "$llvm/llvm-nm" ] || { echo "llvm-tools missing: rustup component add llvm-tools" >&2; exit 2; }

if [ "$ci" = 1 ]; then
  export CARGO_TARGET_DIR="$root/target/release-ci"
  export CARGO_PROFILE_RELEASE_OPT_LEVEL=1 CARGO_PROFILE_RELEASE_LTO=off CARGO_PROFILE_RELEASE_CODEGEN_UNITS=16
else
  export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$root/target}"
fi
tdir=$CARGO_TARGET_DIR
work="$tdir/release-work"
rm -rf "$rel" "$work"
mkdir -p "$rel/lib" "$rel/archives" "$work"

# build TOOL TARGET CRATE_TYPES [RUSTC_ARGS...]: one cargo rustc run; the list of system
# libraries a static link needs ends up in $work/TARGET.native.
build() {
  local tool=$1 target=$2 types=$3
  shift 3
  echo "== $target ($types)"
  # shellcheck disable=SC2086
  if ! nice -n 10 $tool rustc ${cargo_extra:-} -p orient --release --lib --quiet --target "$target" --crate-type "$types" \
    -- --print native-static-libs "$@" >"$work/$target.log" 2>&1; then
    cat "$work/$target.log" >&2
    exit 1
  fi
  sed -n 's/.*native-static-libs: //p' "$work/$target.log" | tail -n 1 >"$work/${target%.2.17}.native"
}
built() { echo "$tdir/${1%.2.17}/release"; }

# strip_static ARCHIVE DEST: a copy without debug information.
strip_static() { "$llvm/llvm-strip" --strip-debug -o "$2" "$1"; }

# Config files for one platform folder: pkg-config and CMake, with the static link
# libraries of that target (scripts/configure-package.sh fills the templates).
# configure PLATFORM NATIVE_LIBS SHARED_FILE SONAME IMPLIB STATIC_FILE
configure() {
  scripts/configure-package.sh --dir "$rel/lib/$1" --cmake-dir cmake --prefix-up 2 --headers "include;bindings/cpp" \
    --libs "$2" --shared "$3" --soname "$4" --implib "$5" --static "$6"
}

# --- Linux, glibc 2.17 floor ---------------------------------------------------------
for arch in x86_64 aarch64 armv7; do
  case $arch in
    armv7) t=armv7-unknown-linux-gnueabihf ;;
    *) t=$arch-unknown-linux-gnu ;;
  esac
  build cargo-zigbuild "$t.2.17" cdylib,staticlib
  d="$rel/lib/linux-$arch"
  mkdir -p "$d"
  "$llvm/llvm-strip" --strip-unneeded -o "$d/liborient.so.$full" "$(built $t)/liborient.so"
  ln -sf "liborient.so.$full" "$d/liborient.so.$abi"
  ln -sf "liborient.so.$abi" "$d/liborient.so"
  strip_static "$(built $t)/liborient.a" "$d/liborient.a"
  configure "linux-$arch" "$(cat "$work/$t.native")" "liborient.so.$full" "liborient.so.$abi" "" liborient.a
done

# --- Linux, musl (fully static programs) ----------------------------------------------
musl_targets="x86_64-unknown-linux-musl:linux-x86_64-musl:cargo aarch64-unknown-linux-musl:linux-aarch64-musl:cargo"
if rustup component list --toolchain nightly --installed 2>/dev/null | grep -q '^rust-src'; then
  musl_targets="$musl_targets armv7-unknown-linux-musleabihf:linux-armv7-musl:nightly"
else
  echo "== armv7 musl skipped: rustup serves no armv7-unknown-linux-musleabihf std and nightly has no rust-src for -Zbuild-std" >&2
fi
for entry in $musl_targets; do
  IFS=: read -r t p how <<<"$entry"
  d="$rel/lib/$p"
  mkdir -p "$d"
  if [ "$how" = nightly ]; then
    # No prebuilt std for this target: build std from nightly's rust-src, and LLVM's
    # libunwind (also in rust-src; rustup's std for the other musl targets carries it).
    RUSTUP_TOOLCHAIN=nightly cargo_extra="-Zbuild-std=std,panic_unwind" build cargo-zigbuild "$t" staticlib
    unwind="$work/libunwind-$t.a"
    src="$(rustc +nightly --print sysroot)/lib/rustlib/src/rust/src/llvm-project/libunwind"
    mkdir -p "$work/unwind-$t"
    for f in libunwind.cpp Unwind-EHABI.cpp UnwindLevel1.c UnwindLevel1-gcc-ext.c \
      UnwindRegistersRestore.S UnwindRegistersSave.S; do
      case $f in
        *.cpp) lang=(-std=c++17 -fno-rtti -fno-exceptions -nostdinc++) ;;
        *.c) lang=(-std=c99) ;;
        *) lang=() ;;
      esac
      python3 -m ziglang cc -target arm-linux-musleabihf -c -O2 -fPIC -funwind-tables \
        -D_LIBUNWIND_IS_NATIVE_ONLY -DNDEBUG -I"$src/include" "${lang[@]}" "$src/src/$f" \
        -o "$work/unwind-$t/$f.o"
    done
    rm -f "$unwind"
    "$llvm/llvm-ar" rcs "$unwind" "$work/unwind-$t"/*.o
  else
    build cargo "$t" staticlib
    unwind="$(rustc --print sysroot)/lib/rustlib/$t/lib/self-contained/libunwind.a"
  fi
  cp "$(built $t)/liborient.a" "$work/$p.a"
  # Rust's musl std leaves the unwinder out of a staticlib (it expects -lunwind): put it
  # in, so `cc -static prog.c liborient.a` is the whole link.
  if [ -n "$unwind" ] && [ -f "$unwind" ]; then "$llvm/llvm-ar" qL "$work/$p.a" "$unwind"; fi
  strip_static "$work/$p.a" "$d/liborient.a"
  native=$(sed 's/-lunwind//' "$work/$t.native")
  configure "$p" "$native" "" "" "" liborient.a
done

# --- Windows x86_64 (MinGW-w64) -------------------------------------------------------
t=x86_64-pc-windows-gnu
build cargo $t cdylib,staticlib
d="$rel/lib/windows-x86_64"
mkdir -p "$d"
x86_64-w64-mingw32-strip --strip-unneeded -o "$d/orient.dll" "$(built $t)/orient.dll"
cp "$(built $t)/liborient.dll.a" "$d/liborient.dll.a"
strip_static "$(built $t)/liborient.a" "$d/liborient.a"
{
  echo "LIBRARY orient.dll"
  echo "EXPORTS"
  scripts/check-dist.py --functions include/orient.h
} >"$work/orient.def"
llvm-dlltool -m i386:x86-64 -d "$work/orient.def" -D orient.dll -l "$d/orient.lib"
configure windows-x86_64 "$(cat "$work/$t.native")" orient.dll orient.dll orient.lib liborient.a

# --- macOS universal dylib ------------------------------------------------------------
zig_dir=$(python3 -c 'import ziglang, os; print(os.path.dirname(ziglang.__file__))')
sdk="$work/macos-sdk"
mkdir -p "$sdk/usr/lib"
for l in System c m; do ln -sf "$zig_dir/lib/libc/darwin/libSystem.tbd" "$sdk/usr/lib/lib$l.tbd"; done
slices=()
for t in aarch64-apple-darwin x86_64-apple-darwin; do
  SDKROOT="$sdk" build cargo $t cdylib -C linker=rust-lld -C linker-flavor=ld64.lld \
    -C link-arg=-install_name -C link-arg=@rpath/liborient.dylib
  slices+=("$(built $t)/liborient.dylib")
done
d="$rel/lib/macos-universal"
mkdir -p "$d"
llvm-lipo-14 -create "${slices[@]}" -output "$d/liborient.dylib"
configure macos-universal "" liborient.dylib @rpath/liborient.dylib "" ""

# --- iOS and Android static libraries; Android shared libraries when an NDK is there ------
# The static libraries need no linker. An Android liborient.so needs the NDK's clang
# (ANDROID_NDK_HOME or ANDROID_NDK_ROOT; Debian has no NDK, so CI here has none): it is
# linked for 16 KB pages (build.rs) and checked by scripts/check-page-size.py.
ndk="${ANDROID_NDK_HOME:-${ANDROID_NDK_ROOT:-}}"
ndk_bin=$(ls -d "$ndk"/toolchains/llvm/prebuilt/*/bin 2>/dev/null | head -n 1 || true)
for entry in aarch64-apple-ios:ios-arm64: aarch64-linux-android:android-arm64-v8a:aarch64-linux-android21-clang \
  armv7-linux-androideabi:android-armeabi-v7a:armv7a-linux-androideabi21-clang; do
  IFS=: read -r t p clang <<<"$entry"
  mkdir -p "$rel/lib/$p"
  if [ -n "$clang" ] && [ -n "$ndk_bin" ]; then
    build cargo "$t" cdylib,staticlib -C linker="$ndk_bin/$clang"
    "$llvm/llvm-strip" --strip-unneeded -o "$rel/lib/$p/liborient.so" "$(built $t)/liborient.so"
    scripts/check-page-size.py "$rel/lib/$p/liborient.so"
    shared=liborient.so
  else
    if [ -n "$clang" ]; then echo "== $p: no Android NDK (ANDROID_NDK_HOME), static library only"; fi
    build cargo "$t" staticlib
    shared=""
  fi
  strip_static "$(built $t)/liborient.a" "$rel/lib/$p/liborient.a"
  configure "$p" "$(cat "$work/$t.native")" "$shared" "$shared" "" liborient.a
done

# --- Python: the sdist and the wheels of the libraries above ----------------------------
scripts/release-wheels.sh "$rel" "$rel/python"

# --- shared files, Unity package, archives, checksums ---------------------------------
mkdir -p "$rel/include" "$rel/bindings/cpp"
cp include/orient.h "$rel/include/"
cp bindings/cpp/orient.hpp "$rel/bindings/cpp/"
cp LICENSE-MIT LICENSE-APACHE CHANGELOG.md README.md "$rel/"
if [ "$ci" = 1 ]; then echo "ci" >"$rel/PROFILE"; else echo "release" >"$rel/PROFILE"; fi

scripts/package-unity.sh "$rel/unity" "$rel/lib"
tar -C "$rel/unity" --transform 's|^com.orient.filters|package|' --owner=0 --group=0 \
  -czf "$rel/archives/com.orient.filters-$version.tgz" com.orient.filters

common=(include bindings LICENSE-MIT LICENSE-APACHE CHANGELOG.md README.md)
for d in "$rel"/lib/*/; do
  p=$(basename "$d")
  name="orient-$version-$p"
  if [ "$p" = windows-x86_64 ]; then
    (cd "$out" && python3 -c 'import sys, zipfile, os
z = zipfile.ZipFile(sys.argv[1], "w", zipfile.ZIP_DEFLATED)
for top in sys.argv[2:]:
    if os.path.isfile(top):
        z.write(top)
    for r, _, fs in os.walk(top):
        for f in sorted(fs):
            z.write(os.path.join(r, f))' "$rel/archives/$name.zip" \
      $(for c in "${common[@]}"; do echo "orient-$version/$c"; done) "orient-$version/lib/$p")
  else
    tar -C "$out" --owner=0 --group=0 -czf "$rel/archives/$name.tar.gz" \
      $(for c in "${common[@]}"; do echo "orient-$version/$c"; done) "orient-$version/lib/$p"
  fi
done

(cd "$rel" && find . -type f ! -name SHA256SUMS | sed 's|^\./||' | LC_ALL=C sort | xargs sha256sum >SHA256SUMS)
echo "release $version (ABI $abi) in $rel:"
(cd "$rel" && find lib unity/com.orient.filters/Plugins -type f \( -name '*.so.*' -o -name '*.a' -o -name '*.dll' -o -name '*.lib' -o -name '*.dylib' \) -printf '%10s  %p\n' | LC_ALL=C sort -k2)
ls -l "$rel/archives"
