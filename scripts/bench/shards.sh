#!/usr/bin/env bash
# The scale-out benchmark on one machine: BrainStem baked to every format but obj (glb,ply,vat,bones,morph)
# in one process, against the GNU parallel recipe of docs/commands/bake.md (8 shards, -j nproc) followed by
# `dqskin merge`, each run into a fresh folder, the two alternating, RUNS runs each; prints the medians and
# their ratio.
# Then where the shards' time goes, from the last run of each: every shard's CPU seconds (GNU time) and
# process seconds (parallel's joblog) beside its own --json-progress summary (wall and per-stage
# thread-seconds) and the one-process bake's, and the balance: the longest shard's CPU time against the
# mean, and the shards' sum against one process's. Every shard starts up, loads the model and plans the
# whole bake; the textures' slices and the per-frame files are dealt by cost (docs/DESIGN.md §2.6).
#
# Usage: scripts/bench/shards.sh
# Environment:
#   RUNS       runs of each (default 3; the median is printed)
#   SHARDS     shards (default 8, as in the recipe of docs/commands/bake.md)
#   JOBS       shards run at once (default: nproc)
#   BAKE_ARGS  extra arguments for every bake (e.g. "--fps 10" for a quicker run)
#   BENCH_TMP  folder for the outputs (default build/bench); a run writes about 5 GB, deleted after it
#
# Needs GNU parallel and ../shared/testdata/BrainStem next to the repository. Builds the Release preset's
# dqskin_cli when needed and copies the binary first, so that a rebuild during the run does not disturb
# it. The merged manifest.json of every sharded run must equal the one-process bake's (merge verifies
# every file against the shards' manifests first), or the script fails.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
cd "$ROOT"

for arg in "$@"; do
  case "$arg" in
    -h | --help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "${BASH_SOURCE[0]}"; exit 0 ;;
    *) echo "bench/shards.sh: unknown argument '$arg' (try --help)" >&2; exit 2 ;;
  esac
done

RUNS="${RUNS:-3}"
SHARDS="${SHARDS:-8}"
JOBS="${JOBS:-$(nproc)}"
FORMATS=glb,ply,vat,bones,morph
read -r -a EXTRA <<<"${BAKE_ARGS:-}"
BRAINSTEM="$(cd "$ROOT/.." && pwd)/shared/testdata/BrainStem/BrainStem.glb"

if ! parallel --version 2>/dev/null | grep -q '^GNU parallel'; then
  echo "bench/shards.sh: needs GNU parallel (Debian: apt-get install parallel)" >&2
  exit 1
fi
if [[ ! -f "$BRAINSTEM" ]]; then
  echo "bench/shards.sh: $BRAINSTEM is absent" >&2
  exit 1
fi

# -- build ------------------------------------------------------------------------------------------------
BENCH="$ROOT/build/bench"
mkdir -p "$BENCH"
if ! { [[ -f build/release/build.ninja ]] || cmake --preset release; } >"$BENCH/build.log" 2>&1 ||
  ! cmake --build --preset release --target dqskin_cli >>"$BENCH/build.log" 2>&1; then
  tail -n 20 "$BENCH/build.log" >&2
  echo "bench/shards.sh: the Release build failed (log: build/bench/build.log)" >&2
  exit 1
fi

mkdir -p "${BENCH_TMP:-$BENCH}"
WORK="$(mktemp -d "${BENCH_TMP:-$BENCH}/dqskin-shards.XXXXXX")"
trap 'rm -rf "$WORK"' EXIT
trap 'exit 130' INT
trap 'exit 143' TERM
# A snapshot of this build that later rebuilds cannot change: the installed tree finds its own library.
cmake --install "$ROOT/build/release" --prefix "$WORK/prefix" >/dev/null
ln -sf prefix/bin/dqskin "$WORK/dqskin"
DQSKIN="$WORK/dqskin"
OUT="$WORK/out"

# One shard as parallel runs it, its --json-progress lines kept for the table (the recipe of
# docs/commands/bake.md has --quiet instead; both sides of the comparison print the same progress lines).
# GNU time records each process's CPU seconds (user + system), which the table compares with one
# process's: a shard's wall time depends on what runs beside it.
cat >"$WORK/shard.sh" <<EOF
#!/usr/bin/env bash
exec /usr/bin/time -f '%U %S' -o "$WORK/shard-\$1.cpu" "$DQSKIN" bake "$BRAINSTEM" -o "$OUT" --format $FORMATS \
  --shard "\$1/$SHARDS" --json-progress ${EXTRA[*]} >"$WORK/shard-\$1.jsonl" 2>"$WORK/shard-\$1.stderr"
EOF

now() { date +%s.%N; }
seconds() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", b - a }'; }
median() { sort -g | awk '{ v[NR] = $1 } END { printf "%.2f", v[int((NR + 1) / 2)] }'; }

# Each run starts from an empty folder, emptied before the clock starts (median_seconds of median.sh
# times its runs back to back, which would count the removal of the last run's gigabytes).
run_whole() {  # prints the seconds
  rm -rf "$OUT"
  local t0 t1
  t0="$(now)"
  /usr/bin/time -f '%U %S' -o "$WORK/whole.cpu" "$DQSKIN" bake "$BRAINSTEM" -o "$OUT" --format "$FORMATS" --json-progress \
    "${EXTRA[@]}" >"$WORK/whole.jsonl" 2>"$WORK/whole.stderr" || { tail -n 5 "$WORK/whole.stderr" >&2; return 1; }
  t1="$(now)"
  cp "$OUT/manifest.json" "$WORK/whole-manifest.json"
  seconds "$t0" "$t1"
}
run_sharded() {  # prints the seconds in all, of the shards and of the merge
  rm -rf "$OUT"
  local t0 t1 t2
  t0="$(now)"
  parallel -j "$JOBS" --joblog "$WORK/joblog" bash "$WORK/shard.sh" {} ::: $(seq 0 $((SHARDS - 1))) \
    2>"$WORK/parallel.stderr" || { tail -n 5 "$WORK"/shard-*.stderr "$WORK/parallel.stderr" >&2; return 1; }
  t1="$(now)"
  /usr/bin/time -f '%U %S' -o "$WORK/merge.cpu" "$DQSKIN" merge "$OUT" --quiet 2>"$WORK/merge.stderr" ||
    { cat "$WORK/merge.stderr" >&2; return 1; }
  t2="$(now)"
  echo "$(seconds "$t0" "$t2") $(seconds "$t0" "$t1") $(seconds "$t1" "$t2")"
}

echo "dqskin scale-out benchmark: BrainStem, --format $FORMATS${BAKE_ARGS:+ $BAKE_ARGS}"
echo "  dqskin:  $("$DQSKIN" --version 2>&1 | head -n 1)"
echo "  nproc:   $(nproc), load average before: $(cut -d ' ' -f 1-3 /proc/loadavg)"
echo "  cpu:     $(grep -m1 'model name' /proc/cpuinfo 2>/dev/null | sed 's/.*: //' || echo unknown)"
echo "  sharded: parallel -j $JOBS, $SHARDS shards, then dqskin merge; runs: $RUNS of each, alternating"
echo "  outputs: $(dirname "$WORK") ($(df -h --output=source,fstype "$WORK" 2>/dev/null | tail -n 1 | tr -s ' ')), deleted before each run"
echo

whole_times=()
sharded_times=()
shard_times=()
merge_times=()
for run in $(seq "$RUNS"); do
  whole="$(run_whole)" || { echo "bench/shards.sh: run $run: the one-process bake failed" >&2; exit 1; }
  whole_times+=("$whole")
  sharded="$(run_sharded)" || { echo "bench/shards.sh: run $run: the sharded bake or the merge failed" >&2; exit 1; }
  read -r total shards merge <<<"$sharded"
  sharded_times+=("$total")
  shard_times+=("$shards")
  merge_times+=("$merge")
  if ! cmp -s "$OUT/manifest.json" "$WORK/whole-manifest.json"; then
    echo "bench/shards.sh: run $run: the merged manifest.json differs from the one-process bake's" >&2
    exit 1
  fi
  echo "run $run: one process ${whole_times[-1]} s; $SHARDS shards ${shards} s + merge ${merge} s = ${total} s"
done
rm -rf "$OUT"

whole_median="$(printf '%s\n' "${whole_times[@]}" | median)"
sharded_median="$(printf '%s\n' "${sharded_times[@]}" | median)"
echo
echo "median of $RUNS runs:"
printf '  %-40s %8s s\n' "one process (dqskin bake)" "$whole_median"
printf '  %-40s %8s s\n' "$SHARDS shards (parallel -j $JOBS) + merge" "$sharded_median"
printf '  %-40s %8s s\n' "  of which the shards" "$(printf '%s\n' "${shard_times[@]}" | median)"
printf '  %-40s %8s s\n' "  of which the merge" "$(printf '%s\n' "${merge_times[@]}" | median)"
printf '  %-40s %8s\n' "sharded / one process" "$(awk -v a="$sharded_median" -v b="$whole_median" 'BEGIN { printf "%.2f", a / b }')"

echo
echo "the last runs, per process: process_s is the whole process (for a shard: parallel's joblog), wall_s and"
echo "the stages (thread-seconds, overlapping) are the bake's own summary; start_s = process_s - wall_s"
python3 - "$WORK" "$SHARDS" "${whole_times[-1]}" <<'PY'
import csv, json, os, sys

work, shards, whole_process_s = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
stages = ["load", "sample", "deform", "readback", "encode", "check", "write"]

def summary(path):
    with open(path) as f:
        lines = [json.loads(l) for l in f if '"event":"summary"' in l]
    return lines[-1] if lines else None

process_s = {}
with open(os.path.join(work, "joblog")) as f:
    for row in csv.DictReader(f, delimiter="\t"):
        process_s[int(row["Command"].split()[-1])] = float(row["JobRuntime"])

def cpu(path):
    with open(path) as f:
        user, system = f.read().split()[-2:]
    return float(user) + float(system)

header = ["process", "frames", "files", "GB", "cpu_s", "process_s", "wall_s", "start_s"] + stages
print(("%-10s %6s %6s %6s %7s %9s %7s %7s" + " %8s" * len(stages)) % tuple(header))
rows = [("shard %d" % i, process_s.get(i), cpu(os.path.join(work, "shard-%d.cpu" % i)),
         summary(os.path.join(work, "shard-%d.jsonl" % i))) for i in range(shards)]
totals = {"cpu_s": 0.0, "process_s": 0.0, "wall_s": 0.0, **{k: 0.0 for k in stages}}
for name, proc, cpu_s, s in rows:
    if s is None:
        print("%-10s (no summary)" % name)
        continue
    t = s["stage_s"]
    print(("%-10s %6d %6d %6.2f %7.2f %9.2f %7.2f %7.2f" + " %8.2f" * len(stages)) % (
        (name, s["frames"], s["files_written"], s["bytes"] / 1e9, cpu_s, proc, s["wall_s"], proc - s["wall_s"])
        + tuple(t.get(k, 0.0) for k in stages)))
    totals["cpu_s"] += cpu_s
    totals["process_s"] += proc
    totals["wall_s"] += s["wall_s"]
    for k in stages:
        totals[k] += t.get(k, 0.0)
print(("%-10s %6s %6s %6s %7.2f %9.2f %7.2f %7.2f" + " %8.2f" * len(stages)) % (
    ("shards' sum", "", "", "", totals["cpu_s"], totals["process_s"], totals["wall_s"], totals["process_s"] - totals["wall_s"])
    + tuple(totals[k] for k in stages)))
merge_cpu = cpu(os.path.join(work, "merge.cpu"))
print("%-10s %6s %6s %6s %7.2f" % ("merge", "", "", "", merge_cpu))
w = summary(os.path.join(work, "whole.jsonl"))
whole_cpu = cpu(os.path.join(work, "whole.cpu"))
if w is not None:
    t = w["stage_s"]
    print(("%-10s %6d %6d %6.2f %7.2f %9.2f %7.2f %7.2f" + " %8.2f" * len(stages)) % (
        ("1 process", w["frames"], w["files_written"], w["bytes"] / 1e9, whole_cpu, whole_process_s, w["wall_s"],
         whole_process_s - w["wall_s"])
        + tuple(t.get(k, 0.0) for k in stages)))
    print("deformer: %s" % w.get("deformer", "?"))
cpus = [c for _, _, c, s in rows if s is not None]
mean = sum(cpus) / len(cpus)
print()
print("balance (CPU seconds): longest shard %.2f = %.2f x the mean %.2f (target <= 1.5)" % (max(cpus), max(cpus) / mean, mean))
print("overhead: shards' sum %.2f = %.2f x one process's %.2f (target <= 1.2); with the merge %.2f x" % (
    sum(cpus), sum(cpus) / whole_cpu, whole_cpu, (sum(cpus) + merge_cpu) / whole_cpu))
PY
