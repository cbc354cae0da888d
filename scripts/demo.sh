#!/usr/bin/env bash
# The main demo: replays the bundled BROAD excerpt through Madgwick (9D, then 6D) and
# prints its error against the optical ground truth.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup-debian.sh --demo
export PATH="$HOME/.cargo/bin:$PATH"
cargo build --release --quiet --example replay
for mode in "" "--no-mag"; do
  ./target/release/examples/replay --filter madgwick $mode examples/data/broad_01_excerpt.csv
  echo
done
