#!/usr/bin/env bash
# Copies the three.js player (web/) and the parts of three.js it imports into DIR/player/, so that a
# static server of DIR shows every bake under DIR:
#
#   scripts/install/player.sh out && python3 -m http.server --bind 127.0.0.1 --directory out 8000
#   open http://127.0.0.1:8000/player/?bake=..&clip=Walk
#
# three comes from npm (scripts/install/node_tools.sh, pinned there) into build/release/tools unless
# THREE_DIR names an installed package. Nothing is fetched at run time: the page imports only these files.
set -euo pipefail

if [ $# -ne 1 ]; then
  echo "usage: $0 DIR   (writes DIR/player/)" >&2
  exit 2
fi
root=$(cd "$(dirname "$0")/../.." && pwd)
three=${THREE_DIR:-$root/build/release/tools/node_modules/three}
if [ ! -f "$three/build/three.module.js" ]; then
  "$root/scripts/install/node_tools.sh" "$root/build/release/tools" >&2
  three=$root/build/release/tools/node_modules/three
fi

out=$1/player
mkdir -p "$out"
cp "$root"/web/*.html "$root"/web/*.js "$root"/web/*.css "$out/"
# three.module.js imports three.core.js; GLTFLoader imports two utilities; EXRLoader uses fflate.
for file in LICENSE package.json build/three.module.js build/three.core.js \
            examples/jsm/loaders/GLTFLoader.js examples/jsm/loaders/EXRLoader.js \
            examples/jsm/utils/BufferGeometryUtils.js examples/jsm/utils/SkeletonUtils.js \
            examples/jsm/libs/fflate.module.js; do
  mkdir -p "$out/three/$(dirname "$file")"
  cp "$three/$file" "$out/three/$file"
done
echo "$out"
