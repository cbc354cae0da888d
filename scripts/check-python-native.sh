#!/usr/bin/env bash
# Fails when bindings/python/orient/_native.py differs from what scripts/gen-python.py
# generates from include/orient.h now (run scripts/check-header.sh first: the header
# itself must match the Rust source). Read-only: it generates into a temporary file.
set -euo pipefail
cd "$(dirname "$0")/.."
tmp=$(mktemp)
trap 'rm -f "$tmp"' EXIT
python3 scripts/gen-python.py include/orient.h "$tmp"
if ! cmp -s "$tmp" bindings/python/orient/_native.py; then
  echo "bindings/python/orient/_native.py is stale: run scripts/gen-python.py and commit the result" >&2
  diff -u bindings/python/orient/_native.py "$tmp" | head -40 >&2
  exit 1
fi
echo "Python: bindings/python/orient/_native.py matches scripts/gen-python.py output"
