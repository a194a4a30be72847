#!/usr/bin/env bash
# The geometric diff benchmark: `dqskin diff MODEL.glb OPTIMIZED.glb` of a whole clip beside
# `dqskin bake MODEL.glb --format ply` of the same clip, run in turn, the median of RUNS runs each, with
# their ratio; and the diff's own split: the correspondence's build time (printed by --verbose) and the
# number of times compared (every key time of both files and the midpoints: the diff deforms both files
# at each, the bake one file at 30 fps).
#
# Usage: scripts/bench/diff.sh [MODEL ...]     (default: BrainStem CesiumMan Fox, from ../shared/testdata)
# Environment:
#   RUNS        runs per command (default 3)
#   DIFF_ARGS   extra arguments for `dqskin diff` (e.g. "--backend egl" for the GPU path, "--fps 30")
#   BENCH_TMP   folder for the outputs (default build/bench)
#
# The optimized file is gltfpack's default output (npm gltfpack, scripts/install/node_tools.sh into
# build/release/tools). Builds the Release preset when needed; the binary is copied first.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
cd "$ROOT"
SHARED="$ROOT/../shared/testdata"
RUNS="${RUNS:-3}"
read -r -a EXTRA <<<"${DIFF_ARGS:-}"
TMP="${BENCH_TMP:-build/bench}/diff"
models=("$@")
[ ${#models[@]} -gt 0 ] || models=(BrainStem CesiumMan Fox)

[ -x build/release/app/dqskin ] || { cmake --preset release >/dev/null && cmake --build --preset release -j "$(nproc)"; }
bash scripts/install/node_tools.sh build/release/tools >/dev/null
mkdir -p "$TMP"
# A snapshot of this build that later rebuilds cannot change: the installed tree finds its own library.
cmake --install build/release --prefix "$TMP/prefix" >/dev/null
ln -sf prefix/bin/dqskin "$TMP/dqskin"
DQSKIN="$TMP/dqskin"
GLTFPACK=build/release/tools/node_modules/.bin/gltfpack

# shellcheck source=median.sh
source "$ROOT/scripts/bench/median.sh"

echo "dqskin $($DQSKIN --version 2>/dev/null | head -1); $(nproc) cores; runs: $RUNS (median); diff args: ${EXTRA[*]:-none}"
printf '%-10s %8s %8s %9s %9s %10s %8s\n' model vertices times diff_s bake_s diff/bake corr_s
for model in "${models[@]}"; do
  input="$SHARED/$model/$model.glb"
  if [ ! -f "$input" ]; then
    echo "$model: skipped ($input not found)"
    continue
  fi
  packed="$TMP/$model.gltfpack.glb"
  "$GLTFPACK" -i "$input" -o "$packed" >/dev/null
  report=$("$DQSKIN" diff "$input" "$packed" --json "${EXTRA[@]}" || true)
  timing=$("$DQSKIN" diff "$input" "$packed" --verbose "${EXTRA[@]}" 2>&1 >/dev/null || true)
  vertices=$(echo "$report" | python3 -c 'import json, sys; print(json.load(sys.stdin)["vertices"]["a"])')
  times=$(echo "$report" | python3 -c 'import json, sys; print(sum(len(c["frames"]) for c in json.load(sys.stdin)["clips"]))')
  corr=$(echo "$timing" | sed -n 's/.*correspondence \([0-9.e-]*\) s.*/\1/p')
  diff_s=$(median_seconds "$DQSKIN" diff "$input" "$packed" "${EXTRA[@]}")
  rm -rf "$TMP/bake"
  bake_s=$(median_seconds bash -c "rm -rf '$TMP/bake' && '$DQSKIN' bake '$input' --format ply -o '$TMP/bake'")
  rm -rf "$TMP/bake"
  printf '%-10s %8s %8s %9s %9s %10.2f %8s\n' "$model" "$vertices" "$times" "$diff_s" "$bake_s" \
    "$(awk -v a="$diff_s" -v b="$bake_s" 'BEGIN { print a / b }')" "${corr:-identity}"
done
