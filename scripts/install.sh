#!/usr/bin/env bash
# Installs orient into a prefix: the shared library under its versioned file name with
# the SONAME and development links, the static library, the C header and the C++
# wrapper, a pkg-config file and a relocatable CMake package config.
#
#   scripts/install.sh --prefix /usr/local            builds in release mode first
#   scripts/install.sh --prefix DIR --target aarch64-unknown-linux-gnu
#   scripts/install.sh --prefix DIR --lib-dir DIR     takes liborient.so/.a from DIR
#
# Layout: PREFIX/lib/liborient.so.1.M.P (ABI 1, crate 0.M.P), liborient.so.1 -> it,
# liborient.so -> liborient.so.1, liborient.a, lib/pkgconfig/orient.pc,
# lib/pkgconfig/orient-static.pc, lib/cmake/orient/orientConfig.cmake (targets
# orient::orient, orient::orient_static; version ABI.MINOR.PATCH), include/orient.h,
# include/orient.hpp. (scripts/release.sh builds every other platform.)
set -euo pipefail
cd "$(dirname "$0")/.."

prefix="" target="" libdir=""
while [ $# -gt 0 ]; do
  case "$1" in
    --prefix) prefix="$2"; shift 2 ;;
    --target) target="$2"; shift 2 ;;
    --lib-dir) libdir="$2"; shift 2 ;;
    *) echo "usage: $0 --prefix DIR [--target TRIPLE] [--lib-dir DIR]" >&2; exit 2 ;;
  esac
done
[ -n "$prefix" ] || { echo "usage: $0 --prefix DIR [--target TRIPLE] [--lib-dir DIR]" >&2; exit 2; }

if [ -z "$libdir" ]; then
  if [ -n "$target" ]; then
    cargo build --release -p orient --lib --target "$target"
    libdir="target/$target/release"
  else
    cargo build --release -p orient --lib
    libdir="target/release"
  fi
fi

version=$(sed -n 's/^version = "\(.*\)"/\1/p' Cargo.toml | head -n 1)
abi=$(sed -n 's/^#define ORIENT_ABI_VERSION \([0-9]*\)$/\1/p' include/orient.h)
minor_patch=${version#*.}
full="$abi.$minor_patch"

mkdir -p "$prefix/lib/pkgconfig" "$prefix/lib/cmake/orient" "$prefix/include"
install -m 0755 "$libdir/liborient.so" "$prefix/lib/liborient.so.$full"
ln -sf "liborient.so.$full" "$prefix/lib/liborient.so.$abi"
ln -sf "liborient.so.$abi" "$prefix/lib/liborient.so"
install -m 0644 "$libdir/liborient.a" "$prefix/lib/liborient.a"
install -m 0644 include/orient.h "$prefix/include/orient.h"
install -m 0644 bindings/cpp/orient.hpp "$prefix/include/orient.hpp"
# What a static link needs besides liborient.a (cargo rustc --print native-static-libs
# for linux-gnu targets).
scripts/configure-package.sh --dir "$prefix/lib" --prefix-up 1 --headers include \
  --libs "-lgcc_s -lutil -lrt -lpthread -lm -ldl -lc" --shared "liborient.so.$full" \
  --soname "liborient.so.$abi" --static liborient.a
echo "installed orient $version (ABI $abi) into $prefix"
