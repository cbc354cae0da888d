#!/usr/bin/env bash
# Runs the bench tool (tools/src/bin/bench.rs) RUNS times (default 7), each in a fresh process, and prints per row
# the median and the range over the runs of the Rust, C and batch times, of the first
# anchor's ratio, and (Madgwick, Mahony) of the floor: their arithmetic alone with the
# state in memory (tools/src/bin/bench.rs, module floor). The small filters' times can
# differ between processes of the same binary while the anchors stay put
# (docs/PERFORMANCE.md, "How to read the times"), so a single run can mislead.
set -euo pipefail
cd "$(dirname "$0")/.."
RUNS=${RUNS:-7}
cargo build --release --quiet -p orient-tools --bin bench
out=$(mktemp)
trap 'rm -f "$out"' EXIT
for _ in $(seq "$RUNS"); do
  target/release/bench | awk 'NF >= 8 && $3 ~ /^[0-9.]+$/ {
    ratio = "-"; for (i = 9; i <= NF; i++) if ($i ~ /^\([0-9.]+x\)$/) { ratio = substr($i, 2, length($i) - 3); break }
    floor = "-"; for (i = 9; i < NF; i++) if ($i == "alone") { floor = $(i + 1); sub(/,$/, "", floor); break }
    print $1 " " $2, $3, $4, $6, ratio, floor }' >> "$out"
done
printf '%-20s %22s %22s %22s %22s %22s\n' "" "Rust ns" "C ns" "batch ns" "Rust/anchor" "floor ns"
printf '%-20s %22s %22s %22s %22s %22s\n' "kind" "median [min-max]" "median [min-max]" "median [min-max]" "median [min-max]" "median [min-max]"
awk -v runs="$RUNS" '
  function stat(list,   n, a, i, j, t) {
    n = split(list, a, " ")
    if (a[1] == "-") return "-"
    for (i = 2; i <= n; i++) { t = a[i]; for (j = i - 1; j >= 1 && a[j] + 0 > t + 0; j--) a[j + 1] = a[j]; a[j + 1] = t }
    return sprintf("%.2f [%.2f-%.2f]", a[int((n + 1) / 2)], a[1], a[n])
  }
  { key = $1 " " $2; if (!(key in seen)) { seen[key] = 1; order[++k] = key }
    r[key] = r[key] " " $3; c[key] = c[key] " " $4; b[key] = b[key] " " $5; x[key] = x[key] " " $6
    f[key] = f[key] " " $7 }
  END { for (i = 1; i <= k; i++) { key = order[i]
    printf "%-20s %22s %22s %22s %22s %22s\n", key, stat(r[key]), stat(c[key]), stat(b[key]), stat(x[key]), stat(f[key]) }
    printf "(%d runs)\n", runs }' "$out"
