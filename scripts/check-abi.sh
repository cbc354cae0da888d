#!/usr/bin/env bash
# Compares include/orient.h with the committed ABI baseline (abi/orient-abi1.h) using
# abi-compliance-checker in header mode, and fails on any binary or source
# incompatibility (a changed struct layout, enum value, signature or removed function);
# then checks that the release library still exports every baseline function
# (abi/orient-abi1.symbols).
# Additions are compatible. After an intended ABI break, raise ORIENT_ABI_VERSION (and
# the SONAME) and commit the new header as abi/orient-abi<N>.h.
set -euo pipefail
cd "$(dirname "$0")/.."
abi=$(sed -n 's/^#define ORIENT_ABI_VERSION \([0-9]*\)$/\1/p' include/orient.h)
baseline="abi/orient-abi$abi.h"
[ -f "$baseline" ] || { echo "no baseline $baseline for ORIENT_ABI_VERSION $abi" >&2; exit 1; }
command -v abi-compliance-checker >/dev/null || { echo "abi-compliance-checker missing (scripts/setup-debian.sh)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# The header's enums have a fixed underlying type only from C23 on; tell the checker.
for side in old new; do
  file="$PWD/$baseline"
  [ "$side" = new ] && file="$PWD/include/orient.h"
  printf '<version>%s</version>\n<headers>%s</headers>\n<gcc_options>-D__STDC_VERSION__=202311L</gcc_options>\n' \
    "$side" "$file" > "$work/$side.xml"
done
# The library half: every function of the baseline is still exported by the release .so.
symbols="abi/orient-abi$abi.symbols"
cargo build --release -p orient --lib --quiet
nm -D --defined-only target/release/liborient.so | awk '$2 == "T" { print $3 }' | sort > "$work/exports"
missing=$(comm -23 "$symbols" "$work/exports")
if [ -n "$missing" ]; then
  echo "liborient.so no longer exports baseline functions: $missing" >&2
  exit 1
fi
echo "abi: all $(wc -l < "$symbols") baseline functions exported"
if (cd "$work" && abi-compliance-checker -lib orient -old old.xml -new new.xml -headers-only \
      -report-path "$work/report.html" > "$work/log" 2>&1); then
  grep -E "compatibility: " "$work/log" | sed 's/^/abi: /'
else
  cat "$work/log" >&2
  echo "include/orient.h breaks the ABI of $baseline (report: rerun this script and keep $work)" >&2
  exit 1
fi
