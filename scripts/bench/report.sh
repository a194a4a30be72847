#!/usr/bin/env bash
# The skinning-report benchmark: `dqskin report MODEL.glb` with every blend on the double-precision CPU
# reference (the default) beside `--fast-cpu` (lbs and dqs on the float deformer, dib on the reference), run
# in turn, the median of RUNS runs each, with the frames measured per second (each frame deformed three
# times, measured per joint, plus one contact sheet per clip) and their ratio.
#
# Usage: scripts/bench/report.sh [MODEL ...]     (default: BrainStem CesiumMan Fox, from ../shared/testdata)
# Environment:
#   RUNS         runs per command (default 3)
#   REPORT_ARGS  extra arguments for `dqskin report` (e.g. "--fps 60", "--backend egl" for the sheets)
#   BENCH_TMP    folder for the outputs (default build/bench)
#
# Builds the Release preset when needed; the binary is copied first.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
cd "$ROOT"
SHARED="$ROOT/../shared/testdata"
RUNS="${RUNS:-3}"
read -r -a EXTRA <<<"${REPORT_ARGS:-}"
TMP="${BENCH_TMP:-build/bench}/report"
models=("$@")
[ ${#models[@]} -gt 0 ] || models=(BrainStem CesiumMan Fox)

[ -x build/release/app/dqskin ] || { cmake --preset release >/dev/null && cmake --build --preset release -j "$(nproc)"; }
mkdir -p "$TMP"
# A snapshot of this build that later rebuilds cannot change: the installed tree finds its own library.
cmake --install build/release --prefix "$TMP/prefix" >/dev/null
ln -sf prefix/bin/dqskin "$TMP/dqskin"
DQSKIN="$TMP/dqskin"

# shellcheck source=median.sh
source "$ROOT/scripts/bench/median.sh"

echo "dqskin $($DQSKIN --version 2>/dev/null | head -1); $(nproc) cores; runs: $RUNS (median); report args: ${EXTRA[*]:-none}"
printf '%-10s %8s %7s %11s %10s %11s %10s %9s\n' model vertices frames reference_s frames/s fast-cpu_s frames/s speed-up
for model in "${models[@]}"; do
  input="$SHARED/$model/$model.glb"
  if [ ! -f "$input" ]; then
    echo "$model: skipped ($input not found)"
    continue
  fi
  rm -rf "$TMP/out"
  "$DQSKIN" report "$input" -o "$TMP/out" -q "${EXTRA[@]}"
  json="$TMP/out/$model/report.json"
  vertices=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["input"]["vertices"])' "$json")
  frames=$(python3 -c 'import json, sys; print(sum(c["frames"] for c in json.load(open(sys.argv[1]))["clips"]))' "$json")
  reference_s=$(median_seconds "$DQSKIN" report "$input" -o "$TMP/out" -q "${EXTRA[@]}")
  fast_s=$(median_seconds "$DQSKIN" report "$input" -o "$TMP/out" -q --fast-cpu "${EXTRA[@]}")
  rm -rf "$TMP/out"
  printf '%-10s %8s %7s %11s %10.1f %11s %10.1f %9.2f\n' "$model" "$vertices" "$frames" "$reference_s" \
    "$(awk -v f="$frames" -v s="$reference_s" 'BEGIN { print f / s }')" "$fast_s" \
    "$(awk -v f="$frames" -v s="$fast_s" 'BEGIN { print f / s }')" \
    "$(awk -v a="$reference_s" -v b="$fast_s" 'BEGIN { print a / b }')"
done
