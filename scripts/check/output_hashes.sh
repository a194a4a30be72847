#!/usr/bin/env bash
# The output fingerprint of a dqskin build: runs a fixed set of commands (info; bake into every format with
# lbs and dqs, on the GL path, the fast CPU deformer and the CPU reference; dib; render; the golden render
# set; diff; report; lint and its fix, also on the bad-skin catalogue) on every bundled rig and every shared
# sample model, and prints one line per file written, "SHA-256  path", followed by each command's exit
# status. Two builds that print the same lines wrote the same bytes: a
# refactor must not change them (compare with diff).
#
# Usage: scripts/check/output_hashes.sh [DQSKIN] > hashes.txt
#   DQSKIN    the binary to run (default build/release/app/dqskin)
# Environment:
#   HASH_TMP  folder for the outputs (default: a new temporary folder, deleted at the end)
#
# The shared sample models are read from ../shared/testdata beside the repository and skipped with a note
# on stderr when it is absent. Renders deform on the CPU reference; their pixels come from the machine's
# OpenGL rasterizer, so compare hashes made on one machine.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
DQSKIN="$(realpath "${1:-$ROOT/build/release/app/dqskin}")"
TMP="${HASH_TMP:-$(mktemp -d)}"
[[ -n "${HASH_TMP:-}" ]] || trap 'rm -rf "$TMP"' EXIT

models=("$ROOT"/testdata/*.gltf)
if [[ -d "$ROOT/../shared/testdata" ]]; then
  while IFS= read -r m; do models+=("$m"); done < <(find "$ROOT/../shared/testdata" -name '*.gl[tb]*' -not -name '*.bin' | sort)
else
  echo "output_hashes.sh: ../shared/testdata not found; only the bundled rigs are hashed" >&2
fi

# Runs one command with its outputs in $TMP/NAME, then prints the hashes of every file there and its status.
run() {
  local name="$1"
  shift
  mkdir -p "$TMP/$name"
  local status=0
  (cd "$TMP/$name" && "$@" >stdout.txt 2>/dev/null) || status=$?
  (cd "$TMP" && find "$name" -type f -print0 | sort -z | xargs -0 sha256sum)
  echo "exit $status  $name"
}

for m in "${models[@]}"; do
  stem="$(basename "$m")"  # with its extension: RiggedSimple comes as .glb and .gltf
  run "info-$stem" "$DQSKIN" info --json "$m"
  # Every format, both blends, on the GL path, the fast CPU deformer and the double-precision reference.
  for mode in dqs lbs; do
    for backend in egl fast-cpu cpu; do
      run "bake-$mode-$backend-$stem" "$DQSKIN" bake "$m" -o out --format glb,ply,obj,vat,bones,morph --fps 10 \
        --mode "$mode" --backend "$backend" --quiet
    done
  done
  run "bake-dib-$stem" "$DQSKIN" bake "$m" -o out --format ply --frames 0:2 --mode dib --quiet
  run "render-$stem" "$DQSKIN" render "$m" -o out --size 96x96 --frames 0:1 --backend cpu --quiet
  # The skinning report (every blend on the CPU reference) and the skin lint with its corrected copy.
  run "report-$stem" "$DQSKIN" report "$m" -o out --fps 10 --image-size 64 --quiet
  run "lint-$stem" "$DQSKIN" lint "$m" --json --max-influences 8 --fix -o fixed.glb
done
for m in "$ROOT"/testdata/bad_skins/*.gltf; do
  run "lint-bad-$(basename "$m")" "$DQSKIN" lint "$m" --json --fix -o fixed.glb
done
stem=twisted_cylinder.gltf
run "render-sheet-$stem" "$DQSKIN" render "$ROOT/testdata/$stem" -o out --size 64x64 --fps 5 --sheet --gif \
  --shade mode-diff --backend cpu --quiet
# The golden render set, as the golden tests and scripts/testdata/make_goldens.sh render it.
run "golden-render" cmake -DDQSKIN="$DQSKIN" -DTESTDATA="$ROOT/testdata" -DOUT=out \
  -P "$ROOT/app/tests/golden_render.cmake"
# Relative paths: the report names them.
run "diff-$stem" "$DQSKIN" diff "../render-$stem/out" "../render-sheet-$stem/out" --json
