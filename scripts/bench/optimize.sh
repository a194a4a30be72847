#!/usr/bin/env bash
# The animation-optimizer benchmark (docs/PERFORMANCE.md "dqskin optimize against gltfpack and
# glTF-Transform"): each shared skinned model through `dqskin optimize` at three budgets, gltfpack (default,
# and -cc) and `gltf-transform resample`, every output measured the same way: its animation data in bytes
# (the accessors animation samplers read, or their compressed bufferViews under EXT_meshopt_compression)
# and its largest surface error against the input by `dqskin diff --mode lbs` over every clip, in scene
# units and as a share of the clip's diagonal; after each of the others, dqskin optimize with that output's
# error as its budget, for the bytes at equal error. Then the time of `dqskin optimize` of BrainStem beside a
# `dqskin bake --format ply` of it.
#
# Usage: scripts/bench/optimize.sh [--quick]
#   --quick  CesiumMan and Fox only, no timing
# Without --quick the 1M-vertex generated character (scripts/testdata/make_big_rig.py: a tube skinned to a
# 64-joint chain, one 4 s clip of 10 keys a second) comes last, with its optimize time and peak memory.
# Environment:
#   DQSKIN     the binary (default build/release/app/dqskin)
#   TOOLS      the npm prefix of scripts/install/node_tools.sh (default build/release/tools)
#   BENCH_TMP  folder for the outputs (default build/bench/optimize)
#   MODELS     the models' paths, space-separated, instead of the list (big_rig: the generated character)
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
DQSKIN="${DQSKIN:-$ROOT/build/release/app/dqskin}"
TOOLS="${TOOLS:-$ROOT/build/release/tools}"
TMP="${BENCH_TMP:-$ROOT/build/bench/optimize}"
SHARED="$ROOT/../shared/testdata"
QUICK=0
[[ "${1:-}" == "--quick" ]] && QUICK=1
for tool in "$DQSKIN" "$TOOLS/node_modules/.bin/gltfpack" "$TOOLS/node_modules/.bin/gltf-transform"; do
  [[ -x "$tool" ]] || { echo "optimize.sh: $tool is missing (build, and run scripts/install/node_tools.sh $TOOLS)" >&2; exit 2; }
done
[[ -d "$SHARED" ]] || { echo "optimize.sh: the shared test models are not at $SHARED" >&2; exit 2; }
mkdir -p "$TMP"

models=("$SHARED/CesiumMan/CesiumMan.glb" "$SHARED/Fox/Fox.glb")
if [[ $QUICK == 0 ]]; then
  python3 "$ROOT/scripts/testdata/make_big_rig.py" "$TMP/big_rig.glb" --vertices 1000000 >/dev/null
  models+=("$SHARED/RiggedFigure/RiggedFigure.glb" "$SHARED/BrainStem/BrainStem.glb" "$TMP/big_rig.glb")
fi
if [[ -n "${MODELS:-}" ]]; then
  read -r -a models <<<"${MODELS//big_rig/$TMP/big_rig.glb}"
  QUICK=1  # no timing section
fi

# Animation bytes of a .glb, and the largest error of B against A over every clip (absolute, relative).
animation_bytes() {
  python3 - "$1" <<'PY'
import json, struct, sys
data = open(sys.argv[1], 'rb').read()
doc = json.loads(data[20:20 + struct.unpack('<I', data[12:16])[0]])
size = {5120: 1, 5121: 1, 5122: 2, 5123: 2, 5125: 4, 5126: 4}
width = {'SCALAR': 1, 'VEC2': 2, 'VEC3': 3, 'VEC4': 4, 'MAT4': 16}
used = {s[k] for a in doc.get('animations', []) for s in a['samplers'] for k in ('input', 'output')}
total, views = 0, set()
for i in used:
    a = doc['accessors'][i]
    view = doc['bufferViews'][a['bufferView']] if 'bufferView' in a else {}
    meshopt = view.get('extensions', {}).get('EXT_meshopt_compression')
    if meshopt:
        if a['bufferView'] not in views: total += meshopt['byteLength']
        views.add(a['bufferView'])
    else:
        total += a['count'] * width[a['type']] * size[a['componentType']]
print(total)
PY
}
worst_error() {
  "$DQSKIN" diff "$1" "$2" --mode lbs --json 2>/dev/null | python3 -c '
import json, sys
d = json.load(sys.stdin)
clips = d.get("clips", [])
print("%.4g %.3g%%" % (max(c["max_error"] for c in clips), 100 * max(c["max_error_relative"] for c in clips)) if clips else "unmatched -")'
}

printf "%-14s %-34s %12s %12s %12s\n" model variant "anim bytes" "max error" "of diagonal"
for model in "${models[@]}"; do
  input="$model"
  stem="$(basename "$model" .glb)"
  printf "%-14s %-34s %12s %12s %12s\n" "$stem" "input" "$(animation_bytes "$input")" 0 "0%"
  # Runs one variant and prints its row; its absolute error is left in $abs.
  run_variant() {
    local name="$1" out="$TMP/$stem.$2.glb" rel
    shift 2
    rm -f "$out"
    abs=""
    if "$@" >/dev/null 2>"$TMP/$stem.err" && [[ -f "$out" ]]; then
      read -r abs rel < <(worst_error "$input" "$out")
      printf "%-14s %-34s %12s %12s %12s\n" "$stem" "$name" "$(animation_bytes "$out")" "$abs" "$rel"
    else
      printf "%-14s %-34s %12s\n" "$stem" "$name" "failed: $(head -c 80 "$TMP/$stem.err")"
    fi
  }
  # A competitor's row, then dqskin optimize with that row's error as its budget: bytes at equal error.
  against() {
    local name="$1" tag="$2"
    shift 2
    run_variant "$name" "$tag" "$@"
    [[ -n "$abs" && "$abs" != unmatched ]] || return 0
    local budget="$abs"
    run_variant "  dqskin optimize at its error" "dqskin-$tag" "$DQSKIN" optimize "$input" -o "$TMP/$stem.dqskin-$tag.glb" --max-error "$budget"
  }
  for budget in 0.1% 0.001 0.0001; do
    run_variant "dqskin optimize --max-error $budget" "dqskin-$budget" "$DQSKIN" optimize "$input" -o "$TMP/$stem.dqskin-$budget.glb" --max-error "$budget"
  done
  against "gltfpack" gltfpack "$TOOLS/node_modules/.bin/gltfpack" -i "$input" -o "$TMP/$stem.gltfpack.glb"
  against "gltfpack -cc" gltfpack-cc "$TOOLS/node_modules/.bin/gltfpack" -cc -i "$input" -o "$TMP/$stem.gltfpack-cc.glb"
  against "gltfpack -noq (animation only)" gltfpack-noq "$TOOLS/node_modules/.bin/gltfpack" -noq -i "$input" -o "$TMP/$stem.gltfpack-noq.glb"
  against "gltf-transform resample" resample "$TOOLS/node_modules/.bin/gltf-transform" resample "$input" "$TMP/$stem.resample.glb"
done

[[ $QUICK == 1 ]] && exit 0
echo
input="$SHARED/BrainStem/BrainStem.glb"
time_of() { local start end; start=$(date +%s.%N); "$@" >/dev/null 2>&1; end=$(date +%s.%N); echo "$end - $start" | bc; }
rm -rf "$TMP/ply"
t_opt=$(time_of "$DQSKIN" optimize "$input" -o "$TMP/BrainStem.timed.glb" --max-error 0.1%)
t_ply=$(time_of "$DQSKIN" bake "$input" -o "$TMP/ply" --format ply -q)
printf "BrainStem: optimize --max-error 0.1%% %.2f s, bake --format ply %.2f s, ratio %.2f\n" "$t_opt" "$t_ply" "$(echo "$t_opt / $t_ply" | bc -l)"
# The 1M-vertex character: its ply bake would write gigabytes, so its time and peak memory alone.
/usr/bin/time -f "%e %M" -o "$TMP/big_rig.time" "$DQSKIN" optimize "$TMP/big_rig.glb" -o "$TMP/big_rig.timed.glb" --max-error 0.1% >/dev/null 2>&1
read -r seconds kib < "$TMP/big_rig.time"
printf "big_rig (1M vertices): optimize --max-error 0.1%% %.2f s, peak memory %d MiB\n" "$seconds" "$((kib / 1024))"
