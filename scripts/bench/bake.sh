#!/usr/bin/env bash
# The end-to-end bake benchmark: `dqskin bake` of real and synthetic characters into every output format,
# one table row per (input, format) with the wall time, frames per second, bytes written and the
# summary's per-stage seconds; beside it the I/O bound: the same bytes (every file the bake wrote, read
# back untimed) written to the same file system with one write call per file and the one syncfs bake
# does, right after the bake once its own writes have reached the disk (io_s, and wall/io, how far bake
# is from it). With Blender installed (`blender` on PATH), a last table bakes
# BrainStem with dqs to one OBJ per frame in Blender headless (Armature modifiers with Preserve Volume,
# scripts/bench/blender_bake_obj.py) beside `dqskin bake --format ply` and `--format obj` of the same frames.
#
# Usage: scripts/bench/bake.sh [--quick]
#   --quick        only CesiumMan and the 100k-vertex character, formats glb and vat
# Environment:
#   BAKE_ARGS      extra arguments for every `dqskin bake` (e.g. "--mode lbs --backend osmesa")
#   BIG_FPS        frames per second for the 1M-vertex character (default 10; "default" for dqskin's 30)
#   BENCH_TMP      folder for the bakes' outputs (default build/bench; e.g. /dev/shm to leave the disk out)
#
# Builds the Release preset when needed, writes the synthetic characters (scripts/testdata/make_big_rig.py) into
# build/bench/ once, and bakes into a temporary folder under build/bench/ (or BENCH_TMP) whose outputs are
# deleted after every run (those of the 1M-vertex character take gigabytes: with the bound's copies a
# full run writes about 100 GB in all, up to 30 GB at a time). The binary is copied first, so that a
# rebuild during the run does not disturb it. The shared sample models are read from ../shared/testdata
# next to the repository; without it they are skipped with a note.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
cd "$ROOT"

QUICK=0
for arg in "$@"; do
  case "$arg" in
    --quick) QUICK=1 ;;
    -h | --help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "${BASH_SOURCE[0]}"; exit 0 ;;
    *) echo "bench/bake.sh: unknown argument '$arg' (try --help)" >&2; exit 2 ;;
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
  echo "bench/bake.sh: the Release build failed (log: build/bench/build.log)" >&2
  exit 1
fi

# -- inputs -----------------------------------------------------------------------------------------------
mkdir -p "${BENCH_TMP:-$BENCH}"
WORK="$(mktemp -d "${BENCH_TMP:-$BENCH}/dqskin-bench.XXXXXX")"
trap 'rm -rf "$WORK"' EXIT
trap 'exit 130' INT
trap 'exit 143' TERM
# A copy of the binary, so that a rebuild during the benchmark does not change or remove it mid-run.
# A snapshot of this build that later rebuilds cannot change: the installed tree finds its own library.
cmake --install "$ROOT/build/release" --prefix "$WORK/prefix" >/dev/null
ln -sf prefix/bin/dqskin "$WORK/dqskin"
DQSKIN="$WORK/dqskin"

make_rig() {  # make_rig FILE VERTICES
  if [[ ! -s "$1" ]]; then
    python3 "$ROOT/scripts/testdata/make_big_rig.py" "$1" --vertices "$2"
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
python3 "$ROOT/scripts/testdata/make_big_rig.py" "$WORK/probe.glb" --vertices 1000 --joints 8 --seconds 0.5 2>/dev/null
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
echo "  io_s: the bake's bytes written again with one write call per file, then one syncfs (the bound);"
echo "  wall/io: bake's wall time over it"
echo

# io_bound FROM TO: writes every file under FROM (read back first, not timed: the same bytes, since a disk
# may take zeros faster than data) to the same path under TO with one write call, then syncs TO's file
# system once, as bake does; prints the seconds of the writes and the sync.
io_bound() {
  python3 - "$1" "$2" <<'PY'
import ctypes, os, sys, time
source, root = sys.argv[1], sys.argv[2]
files = sorted(os.path.relpath(os.path.join(d, f), source) for d, _, names in os.walk(source) for f in names)
seconds = 0.0
for path in files:
    with open(os.path.join(source, path), "rb") as f:
        data = memoryview(f.read())
    target = os.path.join(root, path)
    start = time.perf_counter()
    os.makedirs(os.path.dirname(target), exist_ok=True)
    fd = os.open(target, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
    done = 0
    while done < len(data):  # one call, unless the kernel takes less (over 2 GiB)
        done += os.write(fd, data[done:])
    os.close(fd)
    seconds += time.perf_counter() - start
start = time.perf_counter()
fd = os.open(root, os.O_RDONLY)
ctypes.CDLL(None, use_errno=True).syncfs(fd)
os.close(fd)
print("%.2f" % (seconds + time.perf_counter() - start))
PY
}

fmt_row() { printf '%-12s %-6s %6s %8s %7s %7s %8s %9s %6s %6s %7s %8s %7s %7s  %s\n' "$@"; }
fmt_row input format frames wall_s io_s wall/io frames/s MB load sample deform readback encode write slowest
fmt_row ------------ ------ ------ -------- ------- ------- -------- --------- ------ ------ ------- -------- ------- ------- --------

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
    io_s=-
    if [[ "$status" == 0 ]]; then
      sync -f "$out"  # the bake's writes reach the disk first, so the bound starts as the bake did
      io_s="$(io_bound "$out" "$WORK/bound")"
      rm -rf "$WORK/bound"
    fi
    rm -rf "$out"
    label="$format"
    [[ "$format" == *,* ]] && label="all"
    summary="$(grep '"event":"summary"' "$WORK/stdout" | tail -n 1 || true)"
    if [[ "$status" != 0 || -z "$summary" ]]; then
      failed=1
      fmt_row "$name" "$label" - - - - - - - - - - - - "FAILED (exit $status)"
      sed 's/^/    /' "$WORK/stderr" | tail -n 5
      continue
    fi
    python3 -c '
import json, sys
s = json.loads(sys.argv[1])
stages = ["load", "sample", "deform", "readback", "encode", "write"]
t = s["stage_s"]
wall = s["wall_s"]
io = float(sys.argv[4])
row = [sys.argv[2], sys.argv[3], str(s["frames"]), "%.2f" % wall, "%.2f" % io,
       ("%.1f" % (wall / io) if io > 0 else "-"),
       ("%.1f" % (s["frames"] / wall) if wall > 0 and s["frames"] > 0 else "-"), "%.1f" % (s["bytes"] / 1e6)]
row += ["%.2f" % t[k] for k in stages]
row.append(max(stages, key=lambda k: t[k]))
print("%-12s %-6s %6s %8s %7s %7s %8s %9s %6s %6s %7s %8s %7s %7s  %s" % tuple(row))
' "$summary" "$name" "$label" "$io_s"
  done
done

# -- Blender, when installed ------------------------------------------------------------------------------
BRAINSTEM="$SHARED/BrainStem/BrainStem.glb"
if [[ "$QUICK" == 0 ]] && command -v blender >/dev/null && [[ -f "$BRAINSTEM" ]]; then
  fps=30
  echo
  echo "BrainStem with dqs to one file per frame at $fps fps: $(blender --version 2>/dev/null | head -n 1) headless"
  echo "(scripts/bench/blender_bake_obj.py, Armature modifiers with Preserve Volume) against dqskin; wall_s is the"
  echo "whole process, start-up and import included"
  fmt_blender() { printf '%-34s %6s %8s %9s %10s %10s\n' "$@"; }
  fmt_blender bake frames wall_s frames/s "x full" "x pos-only"
  now() { date +%s.%N; }
  elapsed() { python3 -c 'import sys; print("%.3f" % (float(sys.argv[2]) - float(sys.argv[1])))' "$1" "$2"; }
  declare -A blender_rate=([full]="" [positions-only]="")
  for variant in positions-only full; do
    out="$WORK/blender"
    rm -rf "$out"
    extra=()
    [[ "$variant" == positions-only ]] && extra=(--positions-only)
    t0="$(now)"
    if blender --background --factory-startup --python "$ROOT/scripts/bench/blender_bake_obj.py" -- "$BRAINSTEM" "$out" "$fps" \
      "${extra[@]}" >"$WORK/blender.log" 2>&1; then
      t1="$(now)"
      frames="$(awk '$1 == "frames" { print $2 }' "$WORK/blender.log")"
      row="$(python3 -c 'import sys; f, w = int(sys.argv[1]), float(sys.argv[2]); print("%d %.2f %.1f" % (f, w, f / w))' \
        "$frames" "$(elapsed "$t0" "$t1")")"
      read -r frames wall rate <<<"$row"
      blender_rate[$variant]="$rate"
      fmt_blender "blender obj ($variant)" "$frames" "$wall" "$rate" - -
    else
      failed=1
      fmt_blender "blender obj ($variant)" - - - - "FAILED"
      tail -n 5 "$WORK/blender.log" | sed 's/^/    /'
    fi
    rm -rf "$out"
  done
  for format in ply obj; do
    out="$WORK/out"
    rm -rf "$out"
    t0="$(now)"
    if "$DQSKIN" bake "$BRAINSTEM" -o "$out" --format "$format" --fps "$fps" --mode dqs --force --json-progress \
      "${EXTRA[@]}" >"$WORK/stdout" 2>"$WORK/stderr"; then
      t1="$(now)"
      frames="$(grep '"event":"summary"' "$WORK/stdout" | python3 -c 'import json, sys; print(json.loads(sys.stdin.read())["frames"])')"
      python3 -c 'import sys
f, w = int(sys.argv[1]), float(sys.argv[2])
r = f / w
ratio = lambda b: ("%.1fx" % (r / float(b))) if b else "-"
print("%-34s %6d %8.2f %9.1f %10s %10s" % (sys.argv[5], f, w, r, ratio(sys.argv[3]), ratio(sys.argv[4])))' \
        "$frames" "$(elapsed "$t0" "$t1")" "${blender_rate[full]}" "${blender_rate[positions-only]}" \
        "dqskin bake --format $format"
    else
      failed=1
      fmt_blender "dqskin bake --format $format" - - - - "FAILED"
    fi
    rm -rf "$out"
  done
  echo "x full: frames per second over Blender's OBJ with normals and UVs (what the PLY holds too);"
  echo "x pos-only: over Blender's OBJ with positions alone (its fastest export)"
elif [[ "$QUICK" == 0 ]]; then
  echo
  echo "note: the Blender comparison needs 'blender' on PATH (Debian: apt-get install blender) and BrainStem"
fi

if [[ "$failed" != 0 ]]; then
  echo
  echo "some bakes failed"
  exit 1
fi
