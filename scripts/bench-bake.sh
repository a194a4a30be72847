#!/usr/bin/env bash
# The end-to-end bake benchmark: `dqskin bake` of real and synthetic characters into every output format,
# one table row per (input, format) with the wall time, frames per second, bytes written and the
# summary's per-stage seconds.
#
# Usage: scripts/bench-bake.sh [--quick]
#   --quick        only CesiumMan and the 100k-vertex character, formats glb and vat
# Environment:
#   BAKE_ARGS      extra arguments for every `dqskin bake` (e.g. "--mode lbs --backend osmesa")
#   BIG_FPS        frames per second for the 1M-vertex character (default 10; "default" for dqskin's 30)
#   BENCH_TMP      folder for the bakes' outputs (default build/bench; e.g. /dev/shm to leave the disk out)
#
# Builds the Release preset when needed, writes the synthetic characters (scripts/make_big_rig.py) into
# build/bench/ once, and bakes into a temporary folder under build/bench/ (or BENCH_TMP) whose outputs are
# deleted after every run (those of the 1M-vertex character take gigabytes: a full run writes about
# 50 GB in all, up to 15 GB at a time). The binary is copied first, so that a rebuild during the run does not disturb it. The
# shared sample models are read from ../shared/testdata next to the repository; without it they are
# skipped with a note.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"

QUICK=0
for arg in "$@"; do
  case "$arg" in
    --quick) QUICK=1 ;;
    -h | --help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "${BASH_SOURCE[0]}"; exit 0 ;;
    *) echo "bench-bake.sh: unknown argument '$arg' (try --help)" >&2; exit 2 ;;
  esac
done

read -r -a EXTRA <<<"${BAKE_ARGS:-}"
BIG_FPS="${BIG_FPS:-10}"

# -- build ------------------------------------------------------------------------------------------------
BENCH="$ROOT/build/bench"
mkdir -p "$BENCH"
if ! { [[ -f build/release/build.ninja ]] || cmake --preset release; } >"$BENCH/build.log" 2>&1 ||
  ! cmake --build --preset release --target dqskin_cli >>"$BENCH/build.log" 2>&1; then
  tail -n 20 "$BENCH/build.log" >&2
  echo "bench-bake.sh: the Release build failed (log: build/bench/build.log)" >&2
  exit 1
fi

# -- inputs -----------------------------------------------------------------------------------------------
mkdir -p "${BENCH_TMP:-$BENCH}"
WORK="$(mktemp -d "${BENCH_TMP:-$BENCH}/dqskin-bench.XXXXXX")"
trap 'rm -rf "$WORK"' EXIT
trap 'exit 130' INT
trap 'exit 143' TERM
# A copy of the binary, so that a rebuild during the benchmark does not change or remove it mid-run.
cp "$ROOT/build/release/app/dqskin" "$WORK/dqskin"
DQSKIN="$WORK/dqskin"

make_rig() {  # make_rig FILE VERTICES
  if [[ ! -s "$1" ]]; then
    python3 "$ROOT/scripts/make_big_rig.py" "$1" --vertices "$2"
  fi
}

SHARED="$(cd "$ROOT/.." && pwd)/shared/testdata"
INPUTS=()      # paths
INPUT_ARGS=()  # extra bake arguments per input (one string, word-split)
add_shared() {
  if [[ ! -d "$SHARED" ]]; then return; fi
  if [[ -f "$SHARED/$1" ]]; then
    INPUTS+=("$SHARED/$1")
    INPUT_ARGS+=("")
  else
    echo "note: $SHARED/$1 is missing; skipped"
  fi
}

user_sets_frames=0
for a in "${EXTRA[@]}"; do
  case "$a" in --fps | --fps=* | --frames | --frames=* | --keys | --times | --times=*) user_sets_frames=1 ;; esac
done
big_args=""
big_note="default fps"
if [[ "$user_sets_frames" == 0 && "$BIG_FPS" != "default" ]]; then
  big_args="--fps $BIG_FPS"
  big_note="--fps $BIG_FPS (the default 30 fps of every clip would take several times as long)"
fi

if [[ "$QUICK" == 1 ]]; then
  FORMATS=(glb vat)
  make_rig "$BENCH/big_rig_100k.glb" 100000 2>&1 | sed 's/^/generated /'
  [[ -d "$SHARED" ]] || echo "note: $SHARED is absent; the shared sample models are skipped"
  add_shared CesiumMan/CesiumMan.glb
  INPUTS+=("$BENCH/big_rig_100k.glb")
  INPUT_ARGS+=("")
else
  FORMATS=(glb ply obj vat bones "glb,ply,obj,vat,bones")
  make_rig "$BENCH/big_rig.glb" 1000000 2>&1 | sed 's/^/generated /'
  [[ -d "$SHARED" ]] || echo "note: $SHARED is absent; the shared sample models are skipped"
  add_shared BrainStem/BrainStem.glb
  add_shared raylib_robot/robot.glb
  add_shared Fox/Fox.glb
  add_shared CesiumMan/CesiumMan.glb
  INPUTS+=("$BENCH/big_rig.glb")
  INPUT_ARGS+=("$big_args")
fi

# -- header -----------------------------------------------------------------------------------------------
# The renderer comes from the summary of a tiny bake (bone textures of a 1k-vertex character).
python3 "$ROOT/scripts/make_big_rig.py" "$WORK/probe.glb" --vertices 1000 --joints 8 --seconds 0.5 2>/dev/null
probe="$("$DQSKIN" bake "$WORK/probe.glb" -o "$WORK/probe" --format bones --force --json-progress "${EXTRA[@]}" 2>/dev/null |
  grep '"event":"summary"' | tail -n 1 || true)"
rm -rf "$WORK/probe" "$WORK/probe.glb"
renderer="$(python3 -c 'import json,sys
try:
    s = json.loads(sys.argv[1]); print("%s (%s)" % (s["renderer"] or "none", s["backend"] or "cpu"))
except Exception:
    print("unknown: " + sys.argv[1][:200])' "$probe")"

echo "dqskin bake benchmark$([[ "$QUICK" == 1 ]] && echo " (--quick)")"
echo "  dqskin:    $("$DQSKIN" --version 2>&1 | head -n 1)"
echo "  renderer:  $renderer"
echo "  nproc:     $(nproc)"
echo "  cpu:       $(grep -m1 'model name' /proc/cpuinfo 2>/dev/null | sed 's/.*: //' || echo unknown)"
echo "  bake args: all clips, --force --json-progress${BAKE_ARGS:+ $BAKE_ARGS}"
echo "  outputs:   $(dirname "$WORK") ($(df -h --output=source,fstype "$WORK" 2>/dev/null | tail -n 1 | tr -s ' ')), deleted after each run"
[[ "$QUICK" == 1 ]] || echo "  big_rig:   1M vertices, 64 joints, one 4 s clip, $big_note"
[[ "$QUICK" == 1 ]] || echo "  format 'all' is one bake of glb,ply,obj,vat,bones together"
echo "  frames counts deformed frames: a bones-only bake deforms none"
echo "  stage columns are the summary's thread-seconds (stages overlap and run on several threads, so they"
echo "  can add up to more than the wall time); 'slowest' is the stage with the most seconds"
echo

fmt_row() { printf '%-12s %-6s %6s %8s %8s %9s %6s %6s %7s %8s %7s %7s  %s\n' "$@"; }
fmt_row input format frames wall_s frames/s MB load sample deform readback encode write slowest
fmt_row ------------ ------ ------ -------- -------- --------- ------ ------ ------- -------- ------- ------- --------

failed=0
for i in "${!INPUTS[@]}"; do
  input="${INPUTS[$i]}"
  name="$(basename "$input")"
  name="${name%.*}"
  read -r -a per_input <<<"${INPUT_ARGS[$i]}"
  for format in "${FORMATS[@]}"; do
    out="$WORK/out"
    rm -rf "$out"
    status=0
    "$DQSKIN" bake "$input" -o "$out" --format "$format" --force --json-progress "${per_input[@]}" "${EXTRA[@]}" \
      >"$WORK/stdout" 2>"$WORK/stderr" || status=$?
    rm -rf "$out"
    label="$format"
    [[ "$format" == *,* ]] && label="all"
    summary="$(grep '"event":"summary"' "$WORK/stdout" | tail -n 1 || true)"
    if [[ "$status" != 0 || -z "$summary" ]]; then
      failed=1
      fmt_row "$name" "$label" - - - - - - - - - - "FAILED (exit $status)"
      sed 's/^/    /' "$WORK/stderr" | tail -n 5
      continue
    fi
    python3 -c '
import json, sys
s = json.loads(sys.argv[1])
stages = ["load", "sample", "deform", "readback", "encode", "write"]
t = s["stage_s"]
wall = s["wall_s"]
row = [sys.argv[2], sys.argv[3], str(s["frames"]), "%.2f" % wall,
       ("%.1f" % (s["frames"] / wall) if wall > 0 and s["frames"] > 0 else "-"), "%.1f" % (s["bytes"] / 1e6)]
row += ["%.2f" % t[k] for k in stages]
row.append(max(stages, key=lambda k: t[k]))
print("%-12s %-6s %6s %8s %8s %9s %6s %6s %7s %8s %7s %7s  %s" % tuple(row))
' "$summary" "$name" "$label"
  done
done

if [[ "$failed" != 0 ]]; then
  echo
  echo "some bakes failed"
  exit 1
fi
