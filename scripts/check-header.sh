#!/usr/bin/env bash
# Fails when include/orient.h differs from what cbindgen 0.29.4 generates now, and when
# the release shared library exports anything but the header's functions.
set -euo pipefail
cd "$(dirname "$0")/.."
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
want="cbindgen 0.29.4"
have=$(cbindgen --version 2>/dev/null || true)
[ "$have" = "$want" ] || { echo "need $want, have: ${have:-none}" >&2; exit 2; }
cbindgen --config cbindgen.toml --crate orient --quiet --output "$tmp/orient.h" --symfile "$tmp/symbols"
if ! cmp -s "$tmp/orient.h" include/orient.h; then
  echo "include/orient.h is stale: run scripts/gen-header.sh and commit the result" >&2
  diff -u include/orient.h "$tmp/orient.h" | head -40 >&2
  exit 1
fi
echo "header: include/orient.h matches cbindgen output"
cargo build --release -p orient --lib --quiet
so=target/release/liborient.so
# The symfile is a linker script fragment: '{ name; name; };'
tr -d '{};' < "$tmp/symbols" | tr -s ' \n' '\n' | grep -v '^$' | sort > "$tmp/header-symbols"
nm -D --defined-only "$so" | awk '$2 == "T" { print $3 }' | sort > "$tmp/so-symbols"
if ! diff -u "$tmp/header-symbols" "$tmp/so-symbols"; then
  echo "liborient.so exports differ from the header's functions (- header, + library)" >&2
  exit 1
fi
echo "exports: $(wc -l < "$tmp/so-symbols") functions, exactly the header's"
readelf -d "$so" | grep -q 'SONAME.*liborient.so.1' || { echo "SONAME is not liborient.so.1" >&2; exit 1; }
echo "soname: liborient.so.1"
