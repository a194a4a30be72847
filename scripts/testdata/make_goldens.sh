#!/usr/bin/env bash
# Regenerates the golden images in testdata/golden/ with the Release build of dqskin render (built when
# needed), with the flags of app/tests/golden_render.cmake, which the golden test (app/tests/golden.cmake)
# renders with too. Review every changed image before committing it.
#   scripts/testdata/make_goldens.sh               # build Release if needed, render into testdata/golden/
#   DQSKIN=path/to/dqskin scripts/testdata/make_goldens.sh   # use that binary instead of building
set -euo pipefail
cd "$(dirname "$0")/../.."
if [[ -z "${DQSKIN:-}" ]]; then
  [[ -f build/release/CMakeCache.txt ]] || cmake --preset release
  cmake --build --preset release --target dqskin_cli
  DQSKIN=build/release/app/dqskin
fi
cmake -DDQSKIN="$DQSKIN" -DTESTDATA=testdata -DOUT=testdata/golden -P app/tests/golden_render.cmake
# The goldens are the images; the renders' manifests name this machine's renderer and paths, so they stay out.
find testdata/golden -name render-manifest.json -delete
echo "wrote $(find testdata/golden -name '*.png' | wc -l) images, $(du -sh testdata/golden | cut -f1), into testdata/golden/"
