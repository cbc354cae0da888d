#!/usr/bin/env bash
# Every test: setup, formatting, lints, the generated header and the exported
# symbols, then cargo test (Rust unit and integration tests, doc tests, the C test
# program against the .so and the .a, golden vectors, BROAD recordings in
# ../shared/data).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup-debian.sh
export PATH="$HOME/.cargo/bin:$PATH"

echo "== format"
cargo fmt --all -- --check
echo "== clippy"
cargo clippy --all-targets --quiet -- -D warnings
echo "== header and exports"
scripts/check-header.sh
echo "== cargo test"
cargo test
