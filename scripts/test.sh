#!/usr/bin/env bash
# Installs what dqskin needs, builds it with warnings as errors and runs every test: the Release build
# (then its Slurm scale-out recipe on a one-node cluster of this machine), 60 s of fuzzing the loader and
# the command line (clang, libFuzzer), and the ASan+UBSan build. Exit status 0 when all passed.
#
#   scripts/test.sh            everything, as CI runs it
#   FUZZ_SECONDS=0 scripts/test.sh   without the fuzzing step
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/install/deps.sh

jobs=$(nproc)
build_and_test() {
  echo "== $1: configure and build"
  cmake --preset "$1" >/dev/null
  cmake --build --preset "$1" -j "$jobs"
  bash scripts/install/node_tools.sh "build/$1/tools"  # validator and optimizers, for the glb and geometry diff tests
  echo "== $1: test"
  ctest --preset "$1" -j "$jobs"
  if [ "$1" = release ]; then
    echo "== release: the Slurm scale-out recipe"
    ctest --preset slurm
  fi
}

build_and_test release
if [ "${FUZZ_SECONDS:-60}" -gt 0 ]; then
  echo "== fuzz: ${FUZZ_SECONDS:-60} s"
  FUZZ_JOBS=$jobs bash scripts/check/fuzz.sh "${FUZZ_SECONDS:-60}"
fi
build_and_test sanitize
