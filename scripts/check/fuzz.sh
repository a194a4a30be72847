#!/usr/bin/env bash
# Fuzzes for SECONDS seconds in all: configures the "sanitize" preset (clang, ASan + UBSan; it holds the
# libFuzzer targets too) and builds its "fuzz" build preset (the targets alone, in build/sanitize/fuzz/),
# makes seed corpora under build/fuzz/, checks every truncated prefix of the loader's seeds, then runs,
# with the glTF dictionary, dqskin_fuzz_load (the loader, half the time), then for an eighth each
# dqskin_fuzz_cli (the command line's info, lint and bake on the fuzzed file), dqskin_fuzz_manifest (verify
# and merge on a fuzzed manifest), dqskin_fuzz_exr (diff on a fuzzed EXR) and dqskin_fuzz_bake_folder (diff
# of a bake folder with one file fuzzed). Exits non-zero on any finding: crash,
# sanitizer report, uncaught exception, hang (-timeout), leak, or out-of-memory (-rss_limit_mb /
# -malloc_limit_mb).
#
#   scripts/check/fuzz.sh SECONDS            (from the repository root or anywhere)
#
# Environment: FUZZ_JOBS (build parallelism, default 1), FUZZ_MAX_LEN (largest generated input, default
# 262144: room for 20,000 levels of nesting or thousands of primitives), FUZZ_ARTIFACTS (where crashing inputs are written, default build/fuzz/artifacts), FUZZ_ARGS
# (more libFuzzer flags). The corpora (build/fuzz/corpus, build/fuzz/corpus-cli) grow across runs; seeds
# are re-added each run.
set -euo pipefail

if [ $# -ne 1 ] || ! [[ $1 =~ ^[0-9]+$ ]]; then
  echo "usage: $0 SECONDS" >&2
  exit 2
fi
seconds=$1
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
cd "$root"
build=$root/build/fuzz          # seeds, corpora, logs and findings
bin=$root/build/sanitize        # the instrumented programs (CMakePresets.json)

cmake --preset sanitize >/dev/null
cmake --build --preset fuzz -j "${FUZZ_JOBS:-1}"
fuzzer=$bin/fuzz/dqskin_fuzz_load

# Seed corpus of the loader and the command line: the valid files of the malformed catalogue (the compressed ones too, so that the meshopt and
# Draco decoders are reached) and the project's test data, each at most 1 MiB.
seeds=$build/seeds
corpus=$build/corpus
artifacts=${FUZZ_ARTIFACTS:-$build/artifacts}
mkdir -p "$corpus" "$build/corpus-cli" "$artifacts"
rm -rf "$seeds"
python3 scripts/testdata/make_malformed.py "$build/malformed" >/dev/null
mkdir -p "$seeds"
cp "$build/malformed/valid.gltf" "$build/malformed/valid.glb" "$build/malformed/valid_json_nested_100_deep.gltf" \
  "$build/malformed/value_sampler_wrap_t.gltf" "$build/malformed/value_variant_material.gltf" \
  "$build/malformed/valid_meshopt.glb" "$build/malformed/valid_draco.glb" "$seeds/"
shopt -s nullglob
for f in testdata/*.gltf testdata/*.glb; do
  [ "$(stat -c %s "$f")" -le 1048576 ] && cp "$f" "$seeds/"
done
shopt -u nullglob
echo "fuzz: $(ls "$seeds" | wc -l) seeds, $(ls "$corpus" | wc -l) inputs already in the corpus"

export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:${ASAN_OPTIONS:-}"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:${UBSAN_OPTIONS:-}"

# The loader also looks for external buffers in the current directory (tinygltf searches "."): run in
# an empty one so that the results do not depend on where the script was started.
workdir=$(mktemp -d)
trap 'rm -rf "$workdir"' EXIT
cd "$workdir"

# Truncated-input idiom: the prefixes of every seed (all of them up to 8 KiB), each in an allocation of
# exactly its size.
prefix_list=$(printf '%s:' "$seeds"/*)
DQSKIN_FUZZ_PREFIXES=${prefix_list%:} "$fuzzer" 2>&1 | tail -n 20

# Runs one target: NAME CORPUS SECONDS [libFuzzer flags]; prints its findings and returns libFuzzer's status.
run_target() {
  local name=$1 target_corpus=$2 target_seconds=$3
  shift 3
  local log
  log=$build/fuzz-$name-$(date +%Y%m%d-%H%M%S).log
  local status=0
  # -rss_limit_mb also sets -malloc_limit_mb: one allocation of more than 2 GiB is an out-of-memory finding.
  # shellcheck disable=SC2086
  "$bin/fuzz/dqskin_fuzz_$name" "$target_corpus" "$seeds" \
    -dict="$root/fuzz/glTF.dict" \
    -max_total_time="$target_seconds" -timeout=10 -rss_limit_mb=2048 -detect_leaks=1 \
    -max_len="${FUZZ_MAX_LEN:-262144}" -print_final_stats=1 \
    -artifact_prefix="$artifacts/$name-" "$@" ${FUZZ_ARGS:-} >"$log" 2>&1 || status=$?
  grep -E "^(==[0-9]+==|SUMMARY|artifact_prefix|Test unit written|INFO: seed|Done|fuzz_cli:)" "$log" | tail -n 20 || true
  local executions
  executions=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
  echo "fuzz $name: ${executions:-unknown} executions in ${target_seconds} s; log: $log"
  if [ "$status" -ne 0 ]; then
    echo "fuzz $name: FINDING (libFuzzer exit status $status); reproduce with:" \
      "$bin/fuzz/dqskin_fuzz_$name <the input written above>" >&2
  fi
  return "$status"
}

# Seeds of the newer commands' inputs (docs/SECURITY.md "Every command"): a bake of the twisted cylinder
# (its files for bake folders, its manifest and a shard's for manifests, its VAT textures for EXRs) and the
# crafted EXRs of scripts/testdata/make_hostile_commands.py, each at most 1 MiB.
file_seeds=$build/file-seeds
rm -rf "$file_seeds"
mkdir -p "$file_seeds/manifest" "$file_seeds/exr" "$file_seeds/bake_folder"
bake_flags=(--format ply,obj,glb,vat --frames 0:1 --backend cpu -j 1 --quiet)
"$bin/app/dqskin" bake "$root/testdata/twisted_cylinder.gltf" -o "$file_seeds/bake" "${bake_flags[@]}"
"$bin/app/dqskin" bake "$root/testdata/twisted_cylinder.gltf" -o "$file_seeds/shard" "${bake_flags[@]}" --shard 0/2
cp "$file_seeds/bake/manifest.json" "$file_seeds/shard/manifest.shard-0-of-2.json" "$file_seeds/manifest/"
find "$file_seeds/bake" -type f -size -1025k -exec cp --backup=numbered {} "$file_seeds/bake_folder/" \;
find "$file_seeds/bake" -name '*.exr' -exec cp --backup=numbered {} "$file_seeds/exr/" \;
python3 "$root/scripts/testdata/make_hostile_commands.py" "$file_seeds/hostile" >/dev/null
find "$file_seeds/hostile/diff" -name '*.exr' -size -1025k -exec cp {} "$file_seeds/exr/" \;
for kind in manifest exr bake_folder; do
  mkdir -p "$build/corpus-$kind"
  echo "fuzz: $(ls "$file_seeds/$kind" | wc -l) $kind seeds"
done

# Half the time to the loader, the rest shared by the command line and the three newer kinds of input.
# The commands print; -close_fd_mask=3 silences them (sanitizer reports still reach the log).
load_seconds=$(( (seconds + 1) / 2 ))
share=$(( (seconds - load_seconds) / 4 ))
status=0
run_target load "$corpus" "$load_seconds" || status=$?
if [ "$share" -gt 0 ]; then  # 0 would mean no limit to libFuzzer
  [ "$status" -eq 0 ] && { run_target cli "$build/corpus-cli" "$share" -close_fd_mask=3 || status=$?; }
  for kind in manifest exr bake_folder; do
    [ "$status" -eq 0 ] || break
    seeds=$file_seeds/$kind run_target "$kind" "$build/corpus-$kind" "$share" -close_fd_mask=3 || status=$?
  done
fi
[ "$status" -ne 0 ] && exit "$status"
echo "fuzz: no finding"
