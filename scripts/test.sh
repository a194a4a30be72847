#!/usr/bin/env bash
# Installs what dqskin needs, builds it with warnings as errors and runs the tests: the Release build and
# every one of its tests (then its Slurm scale-out recipe on a one-node cluster of this machine), and the
# ASan+UBSan build (clang), which also holds the libFuzzer targets: 60 s of fuzzing the loader and the
# command line, then the sanitizer run of the tests (a subset: docs/PERFORMANCE.md "CI budget").
# Prints each stage's wall time at the end, also when a stage failed. Exit status 0 when all passed.
#
#   scripts/test.sh                  everything, as CI runs it
#   FUZZ_SECONDS=0 scripts/test.sh   without the fuzzing step
set -euo pipefail
cd "$(dirname "$0")/.."

jobs=$(nproc)
fuzz_seconds=${FUZZ_SECONDS:-60}

# Stage timing: stage NAME ends the running stage and starts NAME; the EXIT trap prints the table, with
# the stage that was running when a command failed marked so.
stage_names=()
stage_times=()
current=""
current_start=0
stage() {
  if [ -n "$current" ]; then
    stage_names+=("$current")
    stage_times+=("$((SECONDS - current_start))")
  fi
  current=$1
  current_start=$SECONDS
  [ -n "$current" ] && echo "== $current"
  return 0
}
print_stage_times() {
  local status=$? i
  local failed=$current
  stage ""
  echo
  echo "stage              wall time"
  for i in "${!stage_names[@]}"; do
    local mark=""
    [ "$status" -ne 0 ] && [ "${stage_names[$i]}" = "$failed" ] && mark="  FAILED (exit status $status)"
    printf '%-18s %4d:%02d%s\n' "${stage_names[$i]}" $((stage_times[i] / 60)) $((stage_times[i] % 60)) "$mark"
  done
  printf '%-18s %4d:%02d\n' total $((SECONDS / 60)) $((SECONDS % 60))
}
trap print_stage_times EXIT

stage install
bash scripts/install/deps.sh
# The glTF tools and three.js of the tests, once: the sanitize build uses the release build's copy.
bash scripts/install/node_tools.sh build/release/tools
mkdir -p build/sanitize
if [ -d build/sanitize/tools ] && [ ! -L build/sanitize/tools ]; then
  bash scripts/install/node_tools.sh build/sanitize/tools  # a copy of its own from an older checkout: kept current
else
  ln -sfn ../release/tools build/sanitize/tools
fi

stage "release build"
cmake --preset release >/dev/null
cmake --build --preset release -j "$jobs"

stage "release test"
ctest --preset release -j "$jobs"

stage slurm
ctest --preset slurm

# One clang build with AddressSanitizer and UndefinedBehaviorSanitizer for the tests and the fuzz
# targets (DQSKIN_FUZZ adds libFuzzer's coverage to every object: CMakeLists.txt).
stage "sanitize build"
cmake --preset sanitize >/dev/null
cmake --build --preset sanitize -j "$jobs"

if [ "$fuzz_seconds" -gt 0 ]; then
  stage fuzz
  FUZZ_JOBS=$jobs bash scripts/check/fuzz.sh "$fuzz_seconds"
fi

stage "sanitize test"
ctest --preset sanitize -j "$jobs"

# The Debian packages, built, checked by lintian and installed into a fresh Debian root (docs/building.md
# "Debian packages"): a second Release build and a root from the apt mirror, so asked for by name.
stage packages
if [ "${DQSKIN_PACKAGES:-0}" = 1 ]; then
  bash scripts/package/debian.sh >build/packages.txt  # its status stops the stage; the last 3 lines are the packages
  mapfile -t debs < <(tail -n 3 build/packages.txt)
  DQSKIN_REQUIRE_ROOT_TEST=1 bash scripts/package/debian_install_test.sh "${debs[@]}"
else
  echo "packages: SKIPPED: DQSKIN_PACKAGES=1 scripts/test.sh builds the Debian packages (a second Release build)," \
       "runs lintian on them and installs them into a fresh Debian root (about 8 minutes more)"
fi
stage ""
