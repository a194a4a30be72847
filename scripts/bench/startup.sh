#!/usr/bin/env bash
# The start-up benchmark: the wall time of whole dqskin processes that do little (`--version`, `info` and
# `lint` on a small bundled rig, and a one-frame glb bake), each run in turn with another dqskin binary
# (an older build) when one is given, so that drift of the machine's speed falls on both alike. Prints
# the median, the fastest and the slowest run of each, the paired ratio new/old, and how many shared
# libraries each binary maps (docs/PERFORMANCE.md "Start-up").
#
# Usage: scripts/bench/startup.sh [--old DQSKIN] [DQSKIN]
#   DQSKIN     the binary to measure (default build/release/app/dqskin)
#   --old BIN  a dqskin binary to compare with
# Environment:
#   RUNS  runs of each command (default 21)
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
OLD=""
NEW="$ROOT/build/release/app/dqskin"
while [[ $# -gt 0 ]]; do
  case "$1" in
    --old) OLD="$(realpath "$2")"; shift 2 ;;
    -h|--help) sed -n '2,13p' "$0"; exit 0 ;;
    *) NEW="$(realpath "$1")"; shift ;;
  esac
done
[[ -x "$NEW" ]] || { echo "startup.sh: $NEW is not an executable (build it: cmake --build --preset release)" >&2; exit 2; }

RIG="$ROOT/testdata/twisted_cylinder.gltf"
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT

for binary in "$NEW" ${OLD:+"$OLD"}; do
  echo "$binary maps $(ldd "$binary" | wc -l) shared libraries"
done
echo

RUNS="${RUNS:-21}" python3 - "$NEW" "$OLD" "$RIG" "$TMP" <<'PY'
import os, statistics, subprocess, sys, time
new, old, rig, tmp = sys.argv[1:5]
runs = int(os.environ["RUNS"])
commands = [
    ("--version", ["--version"]),
    ("info (small rig)", ["info", rig]),
    ("lint (small rig)", ["lint", rig]),
    ("bake glb, 1 frame", ["bake", rig, "-o", os.path.join(tmp, "out"), "--format", "glb", "--frames", "0:1", "-q"]),
]

def once(binary, args):
    start = time.perf_counter()
    subprocess.run([binary] + args, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False)
    return (time.perf_counter() - start) * 1000.0

print(f"| command | new median ms (min-max) |" + (" old median ms (min-max) | new/old |" if old else ""))
print("|---|---|" + ("---|---|" if old else ""))
for name, args in commands:
    a, b = [], []
    once(new, args)  # warm-up: the page cache
    if old:
        once(old, args)
    for _ in range(runs):
        a.append(once(new, args))
        if old:
            b.append(once(old, args))
    row = f"| {name} | {statistics.median(a):.1f} ({min(a):.1f}-{max(a):.1f}) |"
    if old:
        ratio = statistics.median(x / y for x, y in zip(a, b))
        row += f" {statistics.median(b):.1f} ({min(b):.1f}-{max(b):.1f}) | {ratio:.3f} |"
    print(row)
PY
