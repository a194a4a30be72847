#!/usr/bin/env bash
# Installs what dqskin needs, builds the Release preset and runs dqskin with the given arguments.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/install/deps.sh >&2
cmake --preset release >/dev/null
cmake --build --preset release --target dqskin_cli >&2
exec build/release/app/dqskin "$@"
