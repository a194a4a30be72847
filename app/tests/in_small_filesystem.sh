#!/bin/sh
# Runs COMMAND with an empty file system of SIZE (a tmpfs) mounted on FOLDER, in a user and mount namespace
# of its own, so that no root is needed and nothing outside the command sees it. Exits 77 (CTest's skip)
# with the reason when this machine does not allow such namespaces.
#
#   in_small_filesystem.sh SIZE FOLDER COMMAND [ARG...]
size=$1
folder=$2
shift 2
mkdir -p "$folder"
if ! unshare -rm true 2>/dev/null; then
  echo "skipped: user and mount namespaces (unshare -rm) are not allowed here"
  exit 77
fi
# In the inner shell $0 is the size and $1 the folder; the command follows them.
exec unshare -rm sh -c 'mount -t tmpfs -o size="$0" none "$1" && shift && exec "$@"' "$size" "$folder" "$@"
