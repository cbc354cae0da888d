#!/usr/bin/env bash
# Fails when bindings/csharp/Orient.Native.cs differs from what scripts/gen-csharp.py
# generates from include/orient.h now (run scripts/check-header.sh first: the header
# itself must match the Rust source). Read-only: it generates into a temporary file.
set -euo pipefail
cd "$(dirname "$0")/.."
tmp=$(mktemp)
trap 'rm -f "$tmp"' EXIT
python3 scripts/gen-csharp.py include/orient.h "$tmp"
if ! cmp -s "$tmp" bindings/csharp/Orient.Native.cs; then
  echo "bindings/csharp/Orient.Native.cs is stale: run scripts/gen-csharp.py and commit the result" >&2
  diff -u bindings/csharp/Orient.Native.cs "$tmp" | head -40 >&2
  exit 1
fi
echo "C#: bindings/csharp/Orient.Native.cs matches scripts/gen-csharp.py output"
