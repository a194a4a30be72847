#!/usr/bin/env bash
# Frames per second of `dqskin render` on CesiumMan, Fox and BrainStem (from ../shared/testdata) at
# 512x512 and 1024x1024: every clip of CesiumMan and Fox on the 30 fps grid, and the first 60 frames
# (2 s) of BrainStem's 35 s clip. Images go to a temporary folder, removed at the end.
#   scripts/bench/render.sh                       # build Release if needed, then measure
#   DQSKIN=path/to/dqskin scripts/bench/render.sh  # use that binary instead
# Extra arguments are passed on to every render (e.g. --backend osmesa, --samples 1).
# fps counts every frame over the whole run (load, context, first frame included); steady fps leaves
# the first frame out (progress time of the last frame minus that of the first, over frames - 1).
set -euo pipefail
cd "$(dirname "$0")/../.."
if [[ -z "${DQSKIN:-}" ]]; then
  [[ -f build/release/CMakeCache.txt ]] || cmake --preset release
  cmake --build --preset release --target dqskin_cli
  DQSKIN=build/release/app/dqskin
fi
models=../shared/testdata
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

printf '%-10s %-10s %7s %8s %7s %11s  %s\n' model size frames wall_s fps steady_fps renderer
for model in CesiumMan Fox BrainStem; do
  input=$models/$model/$model.glb
  if [[ ! -f $input ]]; then
    echo "$input: not found, skipped" >&2
    continue
  fi
  frames=()
  [[ $model == BrainStem ]] && frames=(--frames 0:59)
  for size in 512x512 1024x1024; do
    "$DQSKIN" render "$input" -o "$out/$model-$size" --size "$size" "${frames[@]}" --json-progress "$@" >"$out/log.jsonl"
    rm -rf "${out:?}/$model-$size"
    python3 - "$model" "$size" "$out/log.jsonl" <<'PY'
import json, sys
model, size, path = sys.argv[1:]
events = [json.loads(line) for line in open(path) if line.startswith("{")]
progress = [e for e in events if e.get("event") == "progress"]
summary = [e for e in events if e.get("event") == "summary"][-1]
n, wall = summary["frames"], summary["wall_s"]
steady = (len(progress) - 1) / (progress[-1]["elapsed_s"] - progress[0]["elapsed_s"]) if len(progress) > 1 else float("nan")
print(f"{model:<10} {size:<10} {n:>7} {wall:>8.2f} {n / wall:>7.1f} {steady:>11.1f}  {summary['renderer']} ({summary['backend']})")
PY
  done
done
