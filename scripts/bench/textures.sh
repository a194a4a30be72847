#!/usr/bin/env bash
# The texture-profile benchmark: `dqskin bake` of BrainStem and the 1M-vertex synthetic character into
# every VAT and bone-texture profile, one row per (input, profile) with the bytes written, the wall time
# with the decode-back check and without it (--no-check), and the summary's check seconds (the
# measuring, planning and checking passes, deformation included); then the lossless OpenEXR compressions
# side by side on BrainStem's textures (bench/exr_compression_bench.cpp).
#
# First, the VAT bake against the disk (docs/PERFORMANCE.md "A VAT bake at the disk's pace"): BrainStem's
# float and half VATs (dqskin profile), baked with --no-check and with the check, beside the time `dd`
# takes to write and sync the same bytes; with --old, the same for another dqskin binary (an older
# build) and whether its files are byte-identical.
#
# Usage: scripts/bench/textures.sh [--quick] [--vat-only] [--old DQSKIN]
#   --quick     BrainStem only, and the compression table on its positions only
#   --vat-only  only the first table
#   --old BIN   a dqskin binary to compare with (its rows are marked "old")
# Environment:
#   RUNS           runs of each command in the first table, the fastest kept (default 2)
#   VAT_ENCODINGS  the first table's encodings (default "float half")
#   BIG_FPS    frames per second for the 1M-vertex character (default 10)
#   BENCH_TMP  folder for the bakes' outputs (default build/bench)
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
cd "$ROOT"

QUICK=0
VAT_ONLY=0
OLD=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --quick) QUICK=1 ;;
    --vat-only) VAT_ONLY=1 ;;
    --old)
      [[ $# -ge 2 && -x "$2" ]] || { echo "bench/textures.sh: --old needs an executable dqskin" >&2; exit 2; }
      OLD="$(cd "$(dirname "$2")" && pwd)/$(basename "$2")"
      shift ;;
    -h | --help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "${BASH_SOURCE[0]}"; exit 0 ;;
    *) echo "bench/textures.sh: unknown argument '$1' (try --help)" >&2; exit 2 ;;
  esac
  shift
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
# A snapshot of this build that later rebuilds cannot change: the installed tree finds its own library.
cmake --install "$ROOT/build/release" --prefix "$WORK/prefix" >/dev/null
ln -sf prefix/bin/dqskin "$WORK/dqskin"
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
if [[ "$QUICK" == 0 && "$VAT_ONLY" == 0 ]]; then
  [[ -s "$BENCH/big_rig.glb" ]] || python3 scripts/testdata/make_big_rig.py "$BENCH/big_rig.glb" --vertices 1000000 | sed 's/^/generated /'
  INPUTS+=("$BENCH/big_rig.glb")
  ARGS+=("--fps $BIG_FPS")
fi

# The VAT bake against the disk: "WALL CPU" seconds of one command (CPU: user and system of it and its
# threads), best of $RUNS by wall time.
seconds() {
  python3 - "$@" <<'PY'
import os, resource, subprocess, sys, time
best = None
for _ in range(int(os.environ.get("RUNS", "2"))):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.monotonic()
    subprocess.run(sys.argv[1:], check=True, stdout=subprocess.DEVNULL)
    took = time.monotonic() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime
    if best is None or took < best[0]:
        best = (took, cpu)
print("%.2f %.2f" % best)
PY
}
if [[ -f "$SHARED/BrainStem/BrainStem.glb" ]]; then
  BRAINSTEM="$SHARED/BrainStem/BrainStem.glb"
  echo "VAT bake against the disk: BrainStem, every frame; nproc $(nproc), load $(cut -d' ' -f1 /proc/loadavg);" \
    "best of ${RUNS:-2} by wall time"
  echo "(bake: --no-check; check: what the checked bake adds; write: dd writing and syncing the bake's images;"
  echo " cpu: user + system seconds on every core)"
  echo
  echo "| binary | encoding | MB | bake s | check s | write s | bake / write | check / bake | bake cpu s | check cpu s | same bytes |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|"
  for encoding in ${VAT_ENCODINGS:-float half}; do
    for which in new old; do
      bin="$DQSKIN"
      [[ "$which" == old ]] && { [[ -n "$OLD" ]] || continue; bin="$OLD"; }
      out="$WORK/vat-$which-$encoding"
      bake=(bake "$BRAINSTEM" --format vat --encoding "$encoding" --quiet --force)
      unchecked="$(seconds "$bin" "${bake[@]}" -o "$out" --no-check)"
      checked="$(seconds "$bin" "${bake[@]}" -o "$out")"
      images=("$out"/BrainStem/*/*.exr)
      bytes="$(cat "${images[@]}" | wc -c)"
      # shellcheck disable=SC2016  # the inner shell expands them
      write="$(seconds bash -c 'cat "$@" | dd of="$0" bs=4M conv=fsync status=none' "$WORK/copy" "${images[@]}")"
      rm -f "$WORK/copy"
      same="-"
      if [[ "$which" == old ]]; then
        same=yes
        for f in "${images[@]}"; do
          cmp -s "$f" "$WORK/vat-new-$encoding/${f#"$out/"}" || same=no
        done
      fi
      # shellcheck disable=SC2086  # "WALL CPU": two words each
      python3 -c 'import sys
w, e, mb, bw, bc, cw, cc, dw, dc, s = sys.argv[1:]
b, c, d = float(bw), float(cw) - float(bw), float(dw)
print("| %s | %s | %.1f | %.2f | %.2f | %.2f | %.2f | %.2f | %.1f | %.1f | %s |" % (
    w, e, float(mb) / 1e6, b, c, d, b / d, c / b, float(bc), float(cc) - float(bc), s))' \
        "$which" "$encoding" "$bytes" $unchecked $checked $write "$same"
    done
  done
  echo
fi
[[ "$VAT_ONLY" == 1 ]] && exit 0

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
