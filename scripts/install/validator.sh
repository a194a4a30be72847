#!/usr/bin/env bash
# Kept for old instructions: installs the Khronos glTF-Validator together with the other Node.js tools,
# through scripts/install/node_tools.sh (one npm call for all of them: a separate call would remove the
# others from PREFIX/node_modules).
#
#   scripts/install/validator.sh build/release/tools
exec bash "$(dirname "$0")/node_tools.sh" "$@"
