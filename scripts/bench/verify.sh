#!/usr/bin/env bash
# The folder-check benchmark: `dqskin verify` of one bake of MODEL (all formats but obj) with 1 hashing
# thread beside one per core, run in turn, the median of RUNS runs each, with the bytes hashed per second
# and their ratio. The files are read from the page cache after the first run (what a check right after a
# bake sees); a folder copied from elsewhere is read from disk once.
#
# Usage: scripts/bench/verify.sh [MODEL]     (default: BrainStem, from ../shared/testdata)
# Environment:
#   RUNS       runs per command (default 3)
#   BENCH_TMP  folder for the outputs (default build/bench)
#
# Builds the Release preset when needed; the binary is copied first.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
cd "$ROOT"
RUNS="${RUNS:-3}"
MODEL="${1:-BrainStem}"
INPUT="$ROOT/../shared/testdata/$MODEL/$MODEL.glb"
TMP="${BENCH_TMP:-build/bench}/verify"
[ -f "$INPUT" ] || { echo "bench-verify: $INPUT not found (the shared test models)" >&2; exit 1; }

[ -x build/release/app/dqskin ] || { cmake --preset release >/dev/null && cmake --build --preset release -j "$(nproc)"; }
rm -rf "$TMP"
mkdir -p "$TMP"
# A snapshot of this build that later rebuilds cannot change: the installed tree finds its own library.
cmake --install build/release --prefix "$TMP/prefix" >/dev/null
ln -sf prefix/bin/dqskin "$TMP/dqskin"
DQSKIN="$TMP/dqskin"

# shellcheck source=median.sh
source "$ROOT/scripts/bench/median.sh"

"$DQSKIN" bake "$INPUT" -o "$TMP/out" --format glb,ply,vat,bones,morph --quiet
"$DQSKIN" verify "$TMP/out" --quiet  # a folder as listed, and its files in the page cache
files=$(find "$TMP/out" -type f | wc -l)
bytes=$(du -sb "$TMP/out" | cut -f1)
echo "$($DQSKIN --version | head -1); $(nproc) cores; runs: $RUNS (median); $MODEL: $files files, $((bytes / 1048576)) MiB"
printf '%-12s %9s %9s\n' threads seconds MiB/s
one=$(median_seconds "$DQSKIN" verify "$TMP/out" --threads 1 --quiet)
all=$(median_seconds "$DQSKIN" verify "$TMP/out" --quiet)
printf '%-12s %9s %9.0f\n' 1 "$one" "$(awk -v b="$bytes" -v s="$one" 'BEGIN { print b / 1048576 / s }')"
printf '%-12s %9s %9.0f\n' "$(nproc) (all)" "$all" "$(awk -v b="$bytes" -v s="$all" 'BEGIN { print b / 1048576 / s }')"
echo "speed-up: $(awk -v a="$one" -v b="$all" 'BEGIN { printf "%.2f", a / b }')x"
