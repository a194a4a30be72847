#!/usr/bin/env bash
# Installs the Node.js glTF tools that the tests use into PREFIX/node_modules, at pinned versions:
#   gltf-validator        the Khronos glTF-Validator (scripts/check/validate_gltf.mjs, the glb_validator tests)
#   gltfpack              meshoptimizer's optimizer (app/tests/geometry_diff.cmake)
#   @gltf-transform/cli   glTF-Transform's `gltf-transform` (app/tests/geometry_diff.cmake)
#   three                 three.js, which the player (web/) imports; scripts/install/player.sh copies it
#   @babylonjs/core       Babylon.js, whose baked vertex animation plays the mat4 bone texture (web/runtimes/)
#   playcanvas            PlayCanvas, whose skinning shader reads the mat3x4 bone texture (web/runtimes/)
#   fflate                the zlib decoder Babylon.js's EXR loader needs for ZIP-compressed EXR, at the
#                         version Babylon.js fetches it at (ExrLoaderGlobalConfiguration.FFLATEUrl), here
#                         so that it comes from disk
# Does nothing when every package is there at its version; otherwise one npm call installs them all.
# The programs are then PREFIX/node_modules/.bin/gltfpack and PREFIX/node_modules/.bin/gltf-transform; they
# need no network to run.
#
#   scripts/install/node_tools.sh build/release/tools
set -euo pipefail

# name@version, one per package. A version change here is a change of what the tests measure: the
# optimizers' output differs between releases.
packages=(
  gltf-validator@2.0.0-dev.3.10
  gltfpack@1.3.0
  @gltf-transform/cli@4.5.1
  three@0.187.0
  @babylonjs/core@9.35.0
  playcanvas@2.23.3
  fflate@0.8.2
)

if [ $# -ne 1 ]; then
  echo "usage: $0 PREFIX   (installs ${packages[*]} into PREFIX/node_modules)" >&2
  exit 2
fi
prefix=$1

# installed NAME VERSION: whether PREFIX/node_modules/NAME/package.json says VERSION.
installed() {
  local package="$prefix/node_modules/$1/package.json"
  [ -f "$package" ] && grep -q "\"version\": *\"$2\"" "$package"
}

missing=()
for p in "${packages[@]}"; do
  name=${p%@*}      # the version follows the last @; a scoped name starts with one
  version=${p##*@}
  installed "$name" "$version" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "node_tools.sh: ${packages[*]} present in $prefix"
  exit 0
fi
if ! command -v npm >/dev/null; then
  echo "node_tools.sh: npm is missing; install Node.js and npm first (scripts/install/deps.sh does)" >&2
  exit 1
fi
mkdir -p "$prefix"
echo "node_tools.sh: installing ${missing[*]} into $prefix"
# All packages in one call: npm replaces PREFIX/node_modules' tree with the one it resolves, so packages
# installed by separate calls with --no-save could be removed by the next one.
npm install --prefix "$prefix" --no-save --no-audit --no-fund --loglevel=error "${packages[@]}"
for p in "${packages[@]}"; do
  if ! installed "${p%@*}" "${p##*@}"; then
    echo "node_tools.sh: npm finished, but $prefix/node_modules/${p%@*} is not version ${p##*@}" >&2
    exit 1
  fi
done
for tool in gltfpack gltf-transform; do
  if [ ! -x "$prefix/node_modules/.bin/$tool" ]; then
    echo "node_tools.sh: npm finished, but $prefix/node_modules/.bin/$tool is missing" >&2
    exit 1
  fi
done
