#!/usr/bin/env bash
# Makes the README's pictures of the commands that draw one and have no golden image: `dqskin report`'s
# worst-frame sheet of the twisted cylinder and `dqskin diff`'s error picture of the bending arm against a
# copy with one elbow key turned by 20°, both from the project's own rigs, into docs/images/. (render's
# pictures are golden images, testdata/golden/.) Both commands write the same bytes on every run, so a
# rerun changes a picture only when the command's drawing changed: review it before committing it.
#   scripts/docs/make_pictures.sh                            # build Release if needed
#   DQSKIN=path/to/dqskin scripts/docs/make_pictures.sh      # use that binary instead of building
set -euo pipefail
cd "$(dirname "$0")/../.."
if [[ -z "${DQSKIN:-}" ]]; then
  [[ -f build/release/CMakeCache.txt ]] || cmake --preset release
  cmake --build --preset release --target dqskin_cli
  DQSKIN=build/release/app/dqskin
fi
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

# report: three worst frames in cells of 160 pixels, small enough for the README.
"$DQSKIN" report testdata/twisted_cylinder.gltf -o "$scratch/report" --image-size 160 --quiet
cp "$scratch/report/twisted_cylinder/worst_twist.png" docs/images/report_worst_frames.png

# diff: the clip fails (any difference over 1e-6 does), so it exits 2 and writes bend.error.png.
python3 scripts/testdata/make_diff_cases.py rotate-key testdata/bending_arm.gltf "$scratch/turned.gltf" \
  --joint elbow --degrees 20 >/dev/null
status=0
"$DQSKIN" diff testdata/bending_arm.gltf "$scratch/turned.gltf" --out "$scratch/diffs" --image-size 256 >/dev/null || status=$?
[[ $status == 2 ]] || { echo "make_pictures: dqskin diff exited $status, expected 2 (a failing clip)" >&2; exit 1; }
cp "$scratch/diffs/bend.error.png" docs/images/diff_error.png

ls -l docs/images/report_worst_frames.png docs/images/diff_error.png
