#!/usr/bin/env bash
# The main demo: replays a BROAD recording through the recommended filter and through
# Madgwick (9D, then 6D) and prints their error against the optical ground truth. The
# recording is trial 15 (fast translation, where linear acceleration misleads filters
# that trust each accelerometer sample) from ../shared/data, or the bundled excerpt of
# trial 01 when ../shared is not beside the repository.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup-debian.sh --demo
export PATH="$HOME/.cargo/bin:$PATH"
cargo build --release --quiet --example replay
rec=../shared/data/broad/15_undisturbed_fast_translation_A.csv
[ -f "$rec" ] || rec=examples/data/broad_01_excerpt.csv
for filter in robust madgwick; do
  for mode in "" "--no-mag"; do
    ./target/release/examples/replay --filter $filter $mode "$rec"
    echo
  done
done
