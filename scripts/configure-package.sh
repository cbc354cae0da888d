#!/usr/bin/env bash
# Writes orient's pkg-config files and CMake package into one library folder, from the
# templates in packaging/. Used by scripts/install.sh (a prefix) and scripts/release.sh
# (each lib/<platform> folder of a release). Every path in the results is relative to
# the file itself, so the folder can be moved.
#   scripts/configure-package.sh --dir LIBDIR --prefix-up N --headers "include;..."
#       --libs "-lpthread ..." --shared FILE --soname NAME --implib FILE --static FILE
# LIBDIR/pkgconfig/orient.pc          the shared library (when --shared is given)
# LIBDIR/pkgconfig/orient-static.pc   the static library by path, with its system libraries
# LIBDIR/CMAKE_DIR/orientConfig.cmake, orientConfigVersion.cmake (--cmake-dir, default
# cmake/orient as in an installed prefix; a release's platform folder uses cmake, which
# find_package searches when CMAKE_PREFIX_PATH names the folder itself)
# --prefix-up: how many folders above LIBDIR the --headers folders are found.
# The package version is the ABI-keyed ABI.MINOR.PATCH (the shared library's file version),
# so find_package(orient 1) matches ABI 1 and no other major.
set -euo pipefail
cd "$(dirname "$0")/.."
dir="" cmake_dir=cmake/orient up=1 headers=include libs="" shared="" soname="" implib="" static=""
while [ $# -gt 0 ]; do
  case "$1" in
    --dir) dir="$2" ;;
    --prefix-up) up="$2" ;;
    --cmake-dir) cmake_dir="$2" ;;
    --headers) headers="$2" ;;
    --libs) libs="$2" ;;
    --shared) shared="$2" ;;
    --soname) soname="$2" ;;
    --implib) implib="$2" ;;
    --static) static="$2" ;;
    *) echo "unknown option $1" >&2; exit 2 ;;
  esac
  shift 2
done
[ -n "$dir" ] || { echo "--dir is required" >&2; exit 2; }
version=$(sed -n 's/^version = "\(.*\)"/\1/p' Cargo.toml | head -n 1)
abi=$(sed -n 's/^#define ORIENT_ABI_VERSION \([0-9]*\)$/\1/p' include/orient.h)
package_version="$abi.${version#*.}"
ups=$(for _ in $(seq "$up"); do printf '/..'; done)
to_libdir=$(printf '%s\n' "$cmake_dir" | tr '/' '\n' | sed 's|.*|/..|' | tr -d '\n')
cflags=$(printf '%s\n' "${headers//;/ }" | tr ' ' '\n' | sed 's|^|-I${prefix}/|' | paste -sd ' ' -)
# -lfoo -> foo for CMake; libc is linked anyway.
cmake_libs=$(printf '%s\n' $libs | sed -n 's/^-l//p' | grep -vx c | paste -sd ';' - || true)
fill() {
  sed -e "s|@VERSION@|$version|g" -e "s|@PACKAGE_VERSION@|$package_version|g" -e "s|@ABI@|$abi|g" \
    -e "s|@PC_PREFIX@|\${pcfiledir}/..$ups|g" -e "s|@PC_CFLAGS@|$cflags|g" \
    -e "s|@LIBS_PRIVATE@|$libs|g" -e "s|@CMAKE_PREFIX_UP@|$ups|g" -e "s|@CMAKE_TO_LIBDIR@|$to_libdir|g" -e "s|@CMAKE_HEADERS@|$headers|g" \
    -e "s|@CMAKE_LIBS@|$cmake_libs|g" -e "s|@SHARED@|$shared|g" -e "s|@SONAME@|$soname|g" \
    -e "s|@IMPLIB@|$implib|g" -e "s|@STATIC@|$static|g" "packaging/$1"
}
mkdir -p "$dir/pkgconfig" "$dir/$cmake_dir"
rm -f "$dir/pkgconfig/orient.pc" "$dir/pkgconfig/orient-static.pc"
if [ -n "$shared" ]; then fill orient.pc.in >"$dir/pkgconfig/orient.pc"; fi
if [ -n "$static" ]; then fill orient-static.pc.in >"$dir/pkgconfig/orient-static.pc"; fi
fill orientConfig.cmake.in >"$dir/$cmake_dir/orientConfig.cmake"
fill orientConfigVersion.cmake.in >"$dir/$cmake_dir/orientConfigVersion.cmake"
