#!/usr/bin/env bash
# The texture-profile benchmark: `dqskin bake` of BrainStem and the 1M-vertex synthetic character into
# every VAT and bone-texture profile, one row per (input, profile) with the bytes written, the wall time
# with the decode-back check and without it (--no-check), and the summary's check seconds (the
# measuring, planning and checking passes, deformation included); then the lossless OpenEXR compressions
# side by side on BrainStem's textures (bench/exr_compression_bench.cpp).
#
# Usage: scripts/bench/textures.sh [--quick]
#   --quick   BrainStem only, and the compression table on its positions only
# Environment:
#   BIG_FPS    frames per second for the 1M-vertex character (default 10)
#   BENCH_TMP  folder for the bakes' outputs (default build/bench)
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
cd "$ROOT"

QUICK=0
for arg in "$@"; do
  case "$arg" in
    --quick) QUICK=1 ;;
    -h | --help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "${BASH_SOURCE[0]}"; exit 0 ;;
    *) echo "bench/textures.sh: unknown argument '$arg' (try --help)" >&2; exit 2 ;;
  esac
done
BIG_FPS="${BIG_FPS:-10}"

BENCH="$ROOT/build/bench"
mkdir -p "$BENCH"
if ! { [[ -f build/release/build.ninja ]] || cmake --preset release; } >"$BENCH/build.log" 2>&1 ||
  ! cmake --build --preset release --target dqskin_cli dqskin_bench_exr >>"$BENCH/build.log" 2>&1; then
  tail -n 20 "$BENCH/build.log" >&2
  echo "bench/textures.sh: the Release build failed (log: build/bench/build.log)" >&2
  exit 1
fi
mkdir -p "${BENCH_TMP:-$BENCH}"
WORK="$(mktemp -d "${BENCH_TMP:-$BENCH}/dqskin-bench-textures.XXXXXX")"
trap 'rm -rf "$WORK"' EXIT
cp "$ROOT/build/release/app/dqskin" "$WORK/dqskin"
cp "$ROOT/build/release/bench/dqskin_bench_exr" "$WORK/bench_exr"
DQSKIN="$WORK/dqskin"

SHARED="$(cd "$ROOT/.." && pwd)/shared/testdata"
INPUTS=()
ARGS=()
if [[ -f "$SHARED/BrainStem/BrainStem.glb" ]]; then
  INPUTS+=("$SHARED/BrainStem/BrainStem.glb")
  ARGS+=("")
else
  echo "note: $SHARED/BrainStem/BrainStem.glb is missing; skipped"
fi
if [[ "$QUICK" == 0 ]]; then
  [[ -s "$BENCH/big_rig.glb" ]] || python3 scripts/testdata/make_big_rig.py "$BENCH/big_rig.glb" --vertices 1000000 | sed 's/^/generated /'
  INPUTS+=("$BENCH/big_rig.glb")
  ARGS+=("--fps $BIG_FPS")
fi

PROFILES=(
  "vat --vat-profile dqskin"
  "vat --vat-profile dqskin --encoding half"
  "vat --vat-profile openvat"
  "vat --vat-profile openvat --encoding png16 --normals separate"
  "vat --vat-profile houdini"
  "vat --vat-profile houdini --encoding half --normals packed"
  "bones --bones-profile dq"
  "bones --bones-profile dq-cocos"
  "bones --bones-profile mat3x4"
  "bones --bones-profile mat4"
)

echo "dqskin texture benchmark$([[ "$QUICK" == 1 ]] && echo " (--quick)")"
echo "  dqskin: $("$DQSKIN" --version 2>&1 | head -n 1)"
echo "  nproc:  $(nproc); cpu: $(grep -m1 'model name' /proc/cpuinfo 2>/dev/null | sed 's/.*: //' || echo unknown)"
echo "  every clip; bytes are the texture files and their side files (manifest left out)"
echo
echo "| input | format and profile | files | MB | wall s, checked | wall s, --no-check | check s | max error | max midpoint error |"
echo "|---|---|---|---|---|---|---|---|---|"
for i in "${!INPUTS[@]}"; do
  input="${INPUTS[$i]}"
  read -r -a input_args <<<"${ARGS[$i]}"
  for profile in "${PROFILES[@]}"; do
    read -r -a p <<<"$profile"
    fmt="${p[0]}"
    rest=("${p[@]:1}")
    run() {  # run FOLDER EXTRA…: one bake; prints its summary JSON line
      rm -rf "$WORK/$1"
      "$DQSKIN" bake "$input" -o "$WORK/$1" --format "$fmt" "${rest[@]}" "${input_args[@]}" --json-progress "${@:2}" |
        grep '"event":"summary"' | tail -n 1
    }
    checked="$(run checked)"
    unchecked="$(run unchecked --no-check)"
    python3 - "$input" "$profile" "$WORK/checked" "$checked" "$unchecked" <<'PY'
import json, os, sys
name, profile, folder, checked, unchecked = sys.argv[1:6]
c, u = json.loads(checked), json.loads(unchecked)
files = 0
size = 0
for root, _, names in os.walk(folder):
    for n in names:
        if n.startswith("manifest"):
            continue
        files += 1
        size += os.path.getsize(os.path.join(root, n))
m = json.load(open(os.path.join(folder, "manifest.json")))
worst = [0.0, 0.0]
for inp in m["inputs"]:
    for a in inp["animations"]:
        for k in a.get("decode_check", {}).values():
            worst[0] = max(worst[0], k["max_error"])
            worst[1] = max(worst[1], k["max_midpoint_error"])
print("| %s | %s | %d | %.1f | %.2f | %.2f | %.2f | %.3g | %.3g |" % (
    os.path.basename(name), profile, files, size / 1e6, c["wall_s"], u["wall_s"], c["stage_s"]["check"],
    worst[0], worst[1]))
PY
  done
done
echo

# Lossless OpenEXR compressions on BrainStem's textures: the float positions of the dqskin profile and the
# half image of the openvat profile.
if [[ -f "$SHARED/BrainStem/BrainStem.glb" ]]; then
  "$DQSKIN" bake "$SHARED/BrainStem/BrainStem.glb" -o "$WORK/exr" --format vat --no-check --quiet
  "$DQSKIN" bake "$SHARED/BrainStem/BrainStem.glb" -o "$WORK/exr" --format vat --vat-profile openvat --no-check --quiet --force
  files=("$WORK/exr/BrainStem/animation0/vat_positions.exr")
  [[ "$QUICK" == 1 ]] || files+=("$WORK/exr/BrainStem/animation0/BrainStem_vat.exr")
  "$WORK/bench_exr" "${files[@]}"
  rm -rf "$WORK/exr"
fi
