#!/usr/bin/env bash
# Installs every Debian 12 package dqskin needs to build, test and run. Idempotent: packages already
# present are left alone, and apt-get is only asked when something is missing.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libglm-dev                                   # vector math and glm::dualquat
  libtinygltf-dev nlohmann-json3-dev libstb-dev  # glTF loading (tinygltf's header needs json + stb)
  libopenimageio-dev                           # EXR/PNG/GIF images
  libimath-dev                                 # half floats, as OpenEXR rounds them (texture encodings)
  libssl-dev                                   # SHA-256 (libcrypto) for bake manifests
  libmeshoptimizer-dev libdraco-dev            # compressed glTF: EXT_meshopt_compression, KHR_draco_mesh_compression
  libcli11-dev                                 # command line
  libnanoflann-dev                             # k-d tree of the geometric diff
  libegl-dev libgl-dev libosmesa6-dev          # headless GL headers: EGL, GL, OSMesa
  libegl-mesa0 libgl1-mesa-dri                 # Mesa's EGL and its drivers (llvmpipe without a GPU)
  libgtest-dev libgmock-dev libbenchmark-dev   # tests and benchmarks
  python3                                      # generators of the test inputs (scripts/make_*.py)
  python3-dev pybind11-dev python3-numpy       # the Python module (python/)
  python3-pytest                               # its tests
  blender                                      # its test inside a real host (python/tests/test_in_blender.py)
  lintian mmdebstrap                           # the Debian packages' checks (scripts/package/)
  clang libclang-rt-14-dev                     # the libFuzzer build (fuzz/)
  chromium                                     # headless WebGL2 (SwiftShader) for the player's tests (web/)
  glslang-tools                                # glslangValidator: the shader kits' compile test (glsl/kits/)
  slurm-wlm                                    # the scale-out recipes' tests: Slurm's daemons and sbatch (scripts/check/slurm_cluster.sh)
  munge                                        # the scale-out recipes' tests: the authentication Slurm's daemons use
  parallel                                     # the scale-out recipes' tests: GNU parallel
)

# Node.js and npm run the glTF tools of scripts/install/node_tools.sh. Debian's are installed
# only when no npm is on the PATH, so that a Node.js installed otherwise is left alone.
command -v npm >/dev/null || packages+=(nodejs npm)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "deps.sh: all ${#packages[@]} packages present"
  exit 0
fi

sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
echo "deps.sh: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
