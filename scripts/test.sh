#!/usr/bin/env bash
# Installs what dqskin needs, builds it twice (Release, and ASan+UBSan) with warnings as errors, and runs
# every test of both builds. Exit status: 0 when everything passed.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/install-deps.sh

jobs=$(nproc)
for preset in release sanitize; do
  echo "== $preset: configure and build"
  cmake --preset "$preset" >/dev/null
  cmake --build --preset "$preset" -j "$jobs"
  echo "== $preset: test"
  ctest --preset "$preset" -j "$jobs"
done
