#!/usr/bin/env bash
# Installs the Khronos glTF-Validator (npm package gltf-validator) into PREFIX/node_modules, for the
# glb_validator test and scripts/validate_gltf.mjs. Does nothing when that version is already there.
#
#   scripts/install-validator.sh build/release/tools
set -euo pipefail

version=2.0.0-dev.3.10
if [ $# -ne 1 ]; then
  echo "usage: $0 PREFIX   (installs gltf-validator@$version into PREFIX/node_modules)" >&2
  exit 2
fi
prefix=$1
package="$prefix/node_modules/gltf-validator/package.json"

if [ -f "$package" ] && grep -q "\"version\": *\"$version\"" "$package"; then
  echo "install-validator: gltf-validator $version present in $prefix"
  exit 0
fi
if ! command -v npm >/dev/null; then
  echo "install-validator: npm is missing; install Node.js and npm first (scripts/install-deps.sh does)" >&2
  exit 1
fi
mkdir -p "$prefix"
echo "install-validator: installing gltf-validator $version into $prefix"
npm install --prefix "$prefix" --no-save --no-audit --no-fund --loglevel=error "gltf-validator@$version"
if ! grep -q "\"version\": *\"$version\"" "$package" 2>/dev/null; then
  echo "install-validator: npm finished, but $package is not version $version" >&2
  exit 1
fi
