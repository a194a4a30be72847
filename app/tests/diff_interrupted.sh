#!/usr/bin/env bash
# `dqskin diff` stopped by SIGTERM mid-way, as bake is (app/interrupt.hpp): it dies of the signal after one
# line on stderr, prints no report, writes no JUnit file, and leaves no temporary: every heat map under its
# final name is a whole PNG. Two folders of 200 pairs of 1024x1024 images that differ everywhere (hard
# links to two files), so that the diff is still writing heat maps when the signal comes.
#
#   diff_interrupted.sh DQSKIN SCRATCH
set -euo pipefail

dqskin=$1
work=$2
fail() {
  echo "diff_interrupted: FAILED: $*" >&2
  exit 1
}

rm -rf "$work"
mkdir -p "$work/A" "$work/B"
header=$'P6\n1024 1024\n255\n'
{ printf '%s' "$header"; head -c $((1024 * 1024 * 3)) /dev/zero; } >"$work/black.ppm"
{ printf '%s' "$header"; head -c $((1024 * 1024 * 3)) /dev/zero | tr '\0' '\200'; } >"$work/grey.ppm"
for i in $(seq -w 1 200); do
  ln "$work/black.ppm" "$work/A/$i.ppm"
  ln "$work/grey.ppm" "$work/B/$i.ppm"
done

"$dqskin" diff "$work/A" "$work/B" --out "$work/heat" --junit "$work/junit.xml" >"$work/stdout" 2>"$work/stderr" &
pid=$!
trap 'kill -KILL "$pid" 2>/dev/null || true' EXIT  # a failing or timed-out test leaves no diff running

# The signal comes once three heat maps are written: the diff is surely mid-way.
for _ in $(seq 1 600); do
  count=$( (find "$work/heat" -name '*.diff.png' 2>/dev/null || true) | wc -l)
  if ((count >= 3)); then break; fi
  kill -0 "$pid" 2>/dev/null || break
  sleep 0.05
done
((count >= 3)) || fail "the diff wrote $count heat maps in 30 s, or ended first"
kill -TERM "$pid"
status=0
wait "$pid" || status=$?

[[ $status == 143 ]] || fail "the diff exited $status, not 143 (SIGTERM)"
lines=$(wc -l <"$work/stderr")
[[ $lines == 1 ]] && grep -q '^dqskin: diff stopped by signal 15; ' "$work/stderr" ||
  fail "stderr is not one line saying the diff was stopped: $(cat "$work/stderr")"
[[ ! -s "$work/stdout" ]] || fail "a report was printed: $(head -c 300 "$work/stdout")"
[[ ! -e "$work/junit.xml" ]] || fail "the JUnit report was written"
leftover=$(find "$work" -name '.*.tmp-*' -o -name '.*.old-*')
[[ -z $leftover ]] || fail "temporaries were left: $leftover"
for png in "$work"/heat/*.diff.png; do
  # A whole PNG ends with its IEND chunk: length 0, "IEND", CRC ae 42 60 82.
  [[ $(tail -c 12 "$png" | od -An -tx1 | tr -d ' \n') == 0000000049454e44ae426082 ]] || fail "$png is not a whole PNG"
done
echo "diff_interrupted: stopped after $(find "$work/heat" -name '*.diff.png' | wc -l) heat maps, by SIGTERM, nothing half-written"
