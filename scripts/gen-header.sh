#!/usr/bin/env bash
# Regenerates include/orient.h with the pinned cbindgen (0.29.4).
set -euo pipefail
cd "$(dirname "$0")/.."
want="cbindgen 0.29.4"
have=$(cbindgen --version 2>/dev/null || true)
if [ "$have" != "$want" ]; then
  echo "need $want (have: ${have:-none}); install: cargo install cbindgen --locked --version 0.29.4" >&2
  exit 2
fi
cbindgen --config cbindgen.toml --crate orient --quiet --output include/orient.h
