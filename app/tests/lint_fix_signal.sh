#!/usr/bin/env bash
# `dqskin lint --fix` stopped by SIGTERM, twice: while it writes its output (its temporary on disk), and
# early, while it reads the input. Each time it must print the one line the other commands print when
# stopped ("dqskin: lint stopped by signal 15; ..."), end by the signal itself (exit status 143 in a shell),
# and leave neither a temporary nor the output. The writing case stops the process (SIGSTOP) when its
# temporary appears, so that the signal lands in that state; the input (make_hostile_commands.py
# unweighted_4m.gltf) makes --fix write 80 MB.
#
#   lint_fix_signal.sh DQSKIN INPUT SCRATCH
#     DQSKIN   the dqskin binary
#     INPUT    the generated unweighted_4m.gltf
#     SCRATCH  a folder of this test's own (emptied first)
set -euo pipefail

dqskin=$1
input=$2
scratch=$3

fail() {
  echo "FAIL: $*"
  exit 1
}

rm -rf "$scratch"
mkdir -p "$scratch"
out=$scratch/fixed.glb

# Seconds since $EPOCHREALTIME was START, to the millisecond.
elapsed() {
  local now=$EPOCHREALTIME
  local us=$(((${now/./} - ${1/./})))
  printf '%d.%03d' $((us / 1000000)) $((us % 1000000 / 1000))
}

# Builtins only (compgen -G), so that the polling does not take the cores the fix runs on.
has_temporary() { compgen -G "$scratch/.fixed.glb.tmp-*" >/dev/null; }

# check_stopped NAME STATUS SECONDS: what a stopped run must leave: the one line, the signal, no file, and
# within 2 s of the signal (interrupt.hpp promises one; the margin is for a busy machine).
check_stopped() {
  local name=$1 status=$2 seconds=$3 err=$scratch/$1.stderr
  echo "$name: exit status $status after ${seconds} s, stderr:"
  sed 's/^/  /' "$err"
  [[ $status == 143 ]] || fail "$name: exit status $status, not 143 (ended by SIGTERM)"
  [[ ${seconds%.*} -lt 2 ]] || fail "$name: took ${seconds} s to stop"
  [[ $(wc -l <"$err") == 1 ]] || fail "$name: stderr is not one line"
  grep -q "^dqskin: lint stopped by signal 15; " "$err" || fail "$name: no 'dqskin: lint stopped by signal 15' line"
  ! has_temporary || fail "$name: a temporary is left: $(compgen -G "$scratch/.fixed.glb.tmp-*")"
  [[ ! -e $out ]] || fail "$name: the output $out was written"
}

# 1. While the output is written.
"$dqskin" lint --fix "$input" -o "$out" >/dev/null 2>"$scratch/writing.stderr" &
pid=$!
trap 'kill -KILL "$pid" 2>/dev/null || true' EXIT  # a failing or timed-out test leaves no process running
stopped=0
deadline=$((SECONDS + 120))
while ((SECONDS < deadline)) && kill -0 "$pid" 2>/dev/null; do
  if has_temporary; then
    kill -STOP "$pid"
    if has_temporary && [[ ! -e $out ]]; then
      kill -TERM "$pid"
      sent=$EPOCHREALTIME
      kill -CONT "$pid"
      stopped=1
      break
    fi
    kill -CONT "$pid"
  fi
  sleep 0.005
done
status=0
wait "$pid" || status=$?
((stopped)) || fail "the fix never had its temporary on disk while running (exit status $status)"
check_stopped writing "$status" "$(elapsed "$sent")"

# 2. Early, while the input is read and linted: 1.5 s into a run of about 5 (past the process's start,
# which takes up to half a second on a busy machine, before any signal handler is installed).
"$dqskin" lint --fix "$input" -o "$out" >/dev/null 2>"$scratch/reading.stderr" &
pid=$!
sleep 1.5
! has_temporary || fail "the fix was already writing after 1.5 s: the early stop would test nothing"
kill -TERM "$pid"
sent=$EPOCHREALTIME
status=0
wait "$pid" || status=$?
trap - EXIT
check_stopped reading "$status" "$(elapsed "$sent")"
rm -rf "$scratch"
echo "stopped while writing and while reading: one line each, no file left"
