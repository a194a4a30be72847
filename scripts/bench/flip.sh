#!/usr/bin/env bash
# The cost of `dqskin diff --metric flip` beside dqskin's idiff-style pass over the same images, run in
# turn, the median of RUNS runs each, with their ratio: one pair of 512x512 renders, one of 2048x2048, and
# two folders of 100 renders (512x512). The pairs are real renders of CesiumMan that differ where they
# would in CI: the same frames blended with lbs (the "golden") and dqs (the candidate). FLIP runs on
# every core (-j nproc) and on one (-j 1), to show what its bands gain.
#
# Usage: scripts/bench/flip.sh
# Environment:
#   RUNS        runs per command (default 3)
#   BENCH_TMP   folder for the renders (default build/bench)
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
cd "$ROOT"
RUNS="${RUNS:-3}"
TMP="${BENCH_TMP:-build/bench}/flip"
MODEL="$ROOT/../shared/testdata/CesiumMan/CesiumMan.glb"
[ -f "$MODEL" ] || { echo "flip.sh: $MODEL not found (the shared test data)" >&2; exit 1; }

[ -x build/release/app/dqskin ] || { cmake --preset release >/dev/null && cmake --build --preset release -j "$(nproc)"; }
mkdir -p "$TMP"
cmake --install build/release --prefix "$TMP/prefix" >/dev/null
DQSKIN="$TMP/prefix/bin/dqskin"

# shellcheck source=median.sh
source "$ROOT/scripts/bench/median.sh"

render() {  # render OUT SIZE MODE FRAME-FLAGS...
  local out=$1 size=$2 mode=$3
  shift 3
  [ -d "$out" ] || "$DQSKIN" render "$MODEL" --mode "$mode" --size "$size" --backend cpu -o "$out" "$@" >/dev/null 2>&1
}
for mode in lbs dqs; do
  render "$TMP/512/$mode" 512x512 "$mode" --times 1.0
  render "$TMP/2048/$mode" 2048x2048 "$mode" --times 1.0
  render "$TMP/folder/$mode" 512x512 "$mode" --fps 50 --frames 0:99
done
one() { find "$TMP/$1/$2" -name '*.png' | sort | head -1; }
count=$(find "$TMP/folder/lbs" -name '*.png' | wc -l)

echo "dqskin $($DQSKIN --version 2>/dev/null | head -1); $(nproc) cores; runs: $RUNS (median)"
printf '%-18s %9s %9s %9s %12s %10s\n' case idiff_s flip_s flip_1_s flip/idiff mean_flip
for case in 512 2048 folder; do
  if [ "$case" = folder ]; then
    a="$TMP/folder/lbs" b="$TMP/folder/dqs" name="folder of $count"
  else
    a=$(one "$case" lbs) b=$(one "$case" dqs) name="${case}x${case}"
  fi
  idiff_s=$(median_seconds "$DQSKIN" diff "$a" "$b")
  flip_s=$(median_seconds "$DQSKIN" diff "$a" "$b" --metric flip -j "$(nproc)")
  flip_1_s=$(median_seconds "$DQSKIN" diff "$a" "$b" --metric flip -j 1)
  # diff exits 2 on a failing pair, as these are: its report is what is read.
  mean=$({ "$DQSKIN" diff "$a" "$b" --metric flip --json || true; } | python3 -c '
import json, sys
pairs = json.load(sys.stdin)["pairs"]
print("%.4f" % (sum(p["mean_error"] for p in pairs) / len(pairs)))')
  printf '%-18s %9s %9s %9s %12.2f %10s\n' "$name" "$idiff_s" "$flip_s" "$flip_1_s" \
    "$(awk -v a="$flip_s" -v b="$idiff_s" 'BEGIN { print a / b }')" "$mean"
done
