#!/usr/bin/env bash
# Installs dqskin's Debian packages into a fresh Debian 12 root (made by mmdebstrap from the machine's apt
# sources, so apt resolves the packages' dependencies as on a user's machine) and uses them there as a
# user would: `dqskin --version` and a bake with the installed CLI, the CMake consumer (cmake/consumer)
# built against libdqskin-dev with find_package(dqskin) and run, and `import dqskin` in Debian's python3
# deforming a clip. The root is removed afterwards. Needs root (mmdebstrap --mode=root) and the apt mirror.
#
# Usage: scripts/package/debian_install_test.sh DEB...   (the three of scripts/package/debian.sh)
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
[ "$#" -ge 1 ] || { echo "usage: debian_install_test.sh DEB..." >&2; exit 2; }
# Without mmdebstrap or root it cannot run: a skip, said so, unless the caller asked for the test itself
# (DQSKIN_REQUIRE_ROOT_TEST=1, as scripts/test.sh does), where it is a failure.
cannot() {
  echo "debian_install_test: SKIPPED: $1"
  [ "${DQSKIN_REQUIRE_ROOT_TEST:-0}" = 1 ] && exit 1
  exit 0
}
command -v mmdebstrap >/dev/null || cannot "mmdebstrap is missing (scripts/install/deps.sh)"
[ "$(id -u)" -eq 0 ] || cannot "mmdebstrap --mode=root needs root"
debs=()
for d in "$@"; do debs+=("$(cd "$(dirname "$d")" && pwd)/$(basename "$d")"); done

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir "$work/in"
cp "${debs[@]}" "$work/in/"
cp -r "$ROOT/cmake/consumer" "$work/in/consumer"
cp "$ROOT/testdata/bending_arm.gltf" "$work/in/"

# Inside the root, after the packages are installed. Each step prints what it checked.
cat >"$work/in/check.sh" <<'CHECK'
set -eu
cd /tmp/in
dqskin --version
dqskin bake bending_arm.gltf -o /tmp/out --format ply,vat --fps 4 >/dev/null
fail() { echo "FAILED: $1"; exit 1; }
[ -f /tmp/out/manifest.json ] || fail "the installed CLI wrote no manifest"
[ "$(find /tmp/out -name '*.ply' | wc -l)" -eq 5 ] || fail "the installed CLI did not write 5 ply frames"
echo "installed CLI: baked 5 ply frames"
[ -f /usr/share/dqskin/player/index.html ] || fail "no player in /usr/share/dqskin/player"
echo "player: /usr/share/dqskin/player/index.html"
cmake -S consumer -B /tmp/consumer-build >/dev/null
cmake --build /tmp/consumer-build >/dev/null
/tmp/consumer-build/dqskin_consumer bending_arm.gltf
python3 -c '
import dqskin
asset = dqskin.load("bending_arm.gltf")
frames = asset.deform("bend", asset.clip("bend").key_times, backend="fast-cpu")
print("python3:", dqskin.__file__, frames.positions.shape)
'
CHECK

mmdebstrap --mode=root --variant=apt --include=build-essential,cmake \
  --customize-hook="copy-in $work/in /tmp" \
  --customize-hook='chroot "$1" sh -c "apt-get install -y -q /tmp/in/*.deb >/dev/null"' \
  --customize-hook='chroot "$1" sh /tmp/in/check.sh >"$1/tmp/in/check.log" 2>&1 || { cat "$1/tmp/in/check.log"; exit 1; }' \
  --customize-hook="copy-out /tmp/in/check.log $work" \
  bookworm "$work/root" 2>"$work/mmdebstrap.log" || { cat "$work/mmdebstrap.log" >&2; exit 1; }
sed 's/^/debian_install_test: /' "$work/check.log"
echo "debian_install_test: OK"
