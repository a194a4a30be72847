#!/usr/bin/env bash
# Builds dqskin's Debian packages (dqskin, libdqskin-dev, python3-dqskin: cmake/debian_packages.cmake)
# from a Release build installed under /usr, into build/deb/packages, and runs lintian on them. Prints the
# packages' paths, one per line, last.
#
# Usage: scripts/package/debian.sh
# Environment:
#   BUILD   build folder (default build/deb)
#   JOBS    parallel compile jobs (default: every core)
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
cd "$ROOT"
BUILD="${BUILD:-build/deb}"
JOBS="${JOBS:-$(nproc)}"
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)

# Installed under /usr, libraries are in the linker's search path: no RUNPATH (lintian's
# custom-library-search-path), and the Python module where Debian's python3 looks.
cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release -DDQSKIN_WERROR=ON -DCMAKE_INSTALL_PREFIX=/usr \
  -DCMAKE_SKIP_INSTALL_RPATH=ON -DDQSKIN_TESTS=OFF -DDQSKIN_BENCH=OFF "${launcher[@]}" >/dev/null
cmake --build "$BUILD" -j "$JOBS" >/dev/null
rm -rf "$BUILD/packages"
(cd "$BUILD" && cpack -G DEB -B "$PWD/packages" >/dev/null)
rm -rf "$BUILD/packages/_CPack_Packages"
mapfile -t debs < <(find "$BUILD/packages" -maxdepth 1 -name '*.deb' | sort)
[ "${#debs[@]}" -eq 3 ] || { echo "debian.sh: expected 3 packages, made ${#debs[@]}" >&2; exit 1; }

# lintian: errors fail; the tags below are what a package built by CPack outside a Debian source tree
# always has (no changelog or copyright file of Debian's own, no manual page yet), and the shared library
# in the dqskin package rather than a libdqskin0.1 of its own (one package for the CLI and the library it
# needs, as the three packages were asked for), named so that any other finding shows.
if command -v lintian >/dev/null; then
  lintian --fail-on error --suppress-tags \
    no-changelog,no-copyright-file,no-manual-page,debian-changelog-file-missing,package-name-doesnt-match-sonames \
    "${debs[@]}"
else
  echo "debian.sh: lintian is missing (scripts/install/deps.sh installs it); the packages were not checked" >&2
fi
printf '%s\n' "${debs[@]}"
