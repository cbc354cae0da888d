#!/usr/bin/env bash
# The main demo: replays the bundled BROAD excerpt through the recommended filter and
# through Madgwick (9D, then 6D) and prints their error against the optical ground truth.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup-debian.sh --demo
export PATH="$HOME/.cargo/bin:$PATH"
cargo build --release --quiet --example replay
for filter in robust madgwick; do
  for mode in "" "--no-mag"; do
    ./target/release/examples/replay --filter $filter $mode examples/data/broad_01_excerpt.csv
    echo
  done
done
