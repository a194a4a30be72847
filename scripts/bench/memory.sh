#!/usr/bin/env bash
# Peak resident memory of every command on one model, at the default --max-memory (2G, a ceiling on all a
# command allocates) unless MAX_MEMORY is set: one line per command with its exit status, the peak
# resident set (GNU time's %M) and the wall time. Resident memory includes what the ceiling does not count
# (the binary and its libraries, the OpenGL driver's own allocations), so it may sit above the ceiling by
# those, never by the data. Results go in docs/SECURITY.md ("Peak memory").
#
#   scripts/bench/memory.sh DQSKIN MODEL SCRATCH [FRAMES]
#     FRAMES  the --frames of the per-frame bakes, render and diff (default: every frame)
set -euo pipefail
dqskin=$1
model=$2
scratch=$3
frames=${4:-}
rm -rf "$scratch"
mkdir -p "$scratch"
limit=()
[[ -n ${MAX_MEMORY:-} ]] && limit=(--max-memory "$MAX_MEMORY")
range=()
[[ -n $frames ]] && range=(--frames "$frames")

run() {
  local name=$1
  shift
  local status=0
  /usr/bin/time -f "%M %e" -o "$scratch/time" "$dqskin" "$@" >"$scratch/out" 2>"$scratch/err" || status=$?
  read -r kib seconds <"$scratch/time" || true
  kib=$(tail -1 "$scratch/time" | cut -d' ' -f1)
  seconds=$(tail -1 "$scratch/time" | cut -d' ' -f2)
  printf '%-22s exit %d  peak %6d MiB  %7.1f s  %s\n' "$name" "$status" $((kib / 1024)) "$seconds" \
    "$( ((status == 0)) || grep -m1 'dqskin:' "$scratch/err" | cut -c1-150)"
}

echo "$(basename "$model"): ${MAX_MEMORY:-default --max-memory}"
run info info "$model" "${limit[@]}"
run lint lint "$model" "${limit[@]}"
run "lint --fix" lint "$model" --fix -o "$scratch/fixed.glb" "${limit[@]}"
for format in glb ply obj; do
  run "bake $format" bake "$model" -o "$scratch/bake-$format" --format "$format" "${range[@]}" --quiet "${limit[@]}"
done
for format in vat bones morph; do
  run "bake $format" bake "$model" -o "$scratch/bake-$format" --format "$format" --quiet "${limit[@]}"
done
# Every format at once, whole and as the shards that hold the most: the morph animation's (shard 0) and the
# textures' head (shard 1) of 8.
all=glb,ply,vat,bones,morph
run "bake $all" bake "$model" -o "$scratch/bake-all" --format "$all" --quiet "${limit[@]}"
rm -rf "$scratch/bake-all"
run "bake all --shard 0/8" bake "$model" -o "$scratch/bake-all" --format "$all" --shard 0/8 --quiet "${limit[@]}"
run "bake all --shard 1/8" bake "$model" -o "$scratch/bake-all" --format "$all" --shard 1/8 --quiet "${limit[@]}"
rm -rf "$scratch/bake-all"
run "verify" verify "$scratch/bake-vat" "${limit[@]}"
run "bake --shard 0/2" bake "$model" -o "$scratch/shards" --format vat --shard 0/2 --quiet "${limit[@]}"
run "bake --shard 1/2" bake "$model" -o "$scratch/shards" --format vat --shard 1/2 --quiet "${limit[@]}"
run "merge" merge "$scratch/shards" "${limit[@]}"
run "render" render "$model" -o "$scratch/render" "${range[@]}" --quiet "${limit[@]}"
run "report" report "$model" -o "$scratch/report" --quiet "${limit[@]}"
run "diff (geometric)" diff "$model" "$model" "${limit[@]}"
rm -rf "$scratch"
