#!/usr/bin/env bash
# The main demo: replays a BROAD recording through the recommended filter (robust) and
# through Madgwick, 9D and 6D, prints their error against the optical ground truth and
# which is more accurate, and draws the error over time (an SVG, path printed).
#
# The recording, and why:
#   - trial 15 (fast translation) from ../shared/data when it is beside the repository:
#     linear acceleration misleads a filter that trusts each accelerometer sample;
#   - otherwise the bundled excerpt of trial 32 (examples/data/broad_32_excerpt.csv: a
#     magnet attached 1 cm from the sensor): a filter that trusts the magnetometer turns
#     its heading with the magnet, while robust uses the magnetometer only while it
#     looks undisturbed and compensates attached magnets.
# Environment (for the tests): ORIENT_SHARED_DATA (default ../shared/data),
# ORIENT_DEMO_REPLAY (a built replay tool: skips the setup and the build),
# ORIENT_DEMO_OUT (directory for the picture, default target/demo).
set -euo pipefail
cd "$(dirname "$0")/.."
replay="${ORIENT_DEMO_REPLAY:-}"
if [ -z "$replay" ]; then
  scripts/setup-debian.sh --demo
  export PATH="$HOME/.cargo/bin:$PATH"
  cargo build --release --quiet -p orient-tools --bin replay
  replay=./target/release/replay
fi
shared="${ORIENT_SHARED_DATA:-../shared/data}"
rec="$shared/broad/15_undisturbed_fast_translation_A.csv"
if [ -f "$rec" ]; then
  echo "recording: BROAD trial 15 (fast translation), $rec"
  echo "why: linear acceleration misleads a filter that trusts each accelerometer sample"
else
  echo "recording: $shared not found, so the bundled excerpt of BROAD trial 32 (a magnet"
  echo "  attached 1 cm from the sensor), examples/data/broad_32_excerpt.csv"
  echo "why: a filter that trusts the magnetometer turns its heading with the magnet;"
  echo "  robust uses the magnetometer only while it looks undisturbed and compensates"
  echo "  attached magnets (its design: docs/ACCURACY.md)"
  rec=examples/data/broad_32_excerpt.csv
fi
out="${ORIENT_DEMO_OUT:-target/demo}"
mkdir -p "$out"
svg="$out/errors.svg"
echo
log=$(mktemp)
trap 'rm -f "$log"' EXIT
"$replay" --filter robust,madgwick --svg "$svg" "$rec" | tee "$log"
echo
"$replay" --filter robust,madgwick --no-mag "$rec" | tee -a "$log"
echo
# The verdict from the numbers just printed: total error, 9D, then 6D with the heading
# offset removed (the last score line of each filter).
awk '
  /^[a-z]+ (9D|6D),/ { kind = $1; dims = $2; sub(",", "", dims) }
  /total/ { for (i = 1; i <= NF; i++) if ($i == "total") total[kind, dims] = $(i + 1) }
  END {
    for (d = 0; d < 2; d++) {
      dims = d == 0 ? "9D" : "6D"
      r = total["robust", dims]; m = total["madgwick", dims]
      verdict = (r + 0 < m + 0) ? "the recommended kind is more accurate" : "Madgwick is more accurate"
      printf "%s: robust %.2f deg, madgwick %.2f deg total error: %s\n", dims, r, m, verdict
    }
  }' "$log"
echo "picture: $svg (error over time; bands where each filter reported rest, an unused magnetometer or accelerometer, a gap)"
