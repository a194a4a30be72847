#!/usr/bin/env bash
# dqskin merge and verify stopped by SIGTERM or SIGINT: exactly one line on stderr saying so, the process
# ended by that signal (as bake is), and the folder as it was: no merged manifest, every shard manifest
# still there, no temporary. The signal is sent once the command has its handlers (SigCgt in
# /proc/PID/status), so that it tests the command, not how fast the binary starts.
#   - a merge of 400,000 listed files (verify/entries_400k), stopped while it reads and checks them;
#   - a merge of 10,000 files that succeeds (verify/mergeable), stopped after 0 to 1.6 s: every run ends
#     stopped with the folder as it was, or merged whole (the signal came after the last step);
#   - a verify of the 400,000 files, stopped by SIGINT.
#
#   interrupt_merge.sh DQSKIN HOSTILE SCRATCH
#     DQSKIN   the dqskin binary
#     HOSTILE  the folder scripts/testdata/make_hostile_commands.py wrote
#     SCRATCH  a folder of this test's own (emptied first; removed when the test passes)
set -euo pipefail

dqskin=$1
hostile=$2
scratch=$3

fail() {
  echo "FAIL: $*"
  exit 1
}

# snapshot FOLDER: every entry, hidden ones included, with its type, size and (for files) SHA-256.
snapshot() {
  (cd "$1" && find . -printf '%p %y %s\n' | sort && find . -type f -exec sha256sum {} + | sort)
}

# wait_for_handlers PID: returns once PID runs dqskin (not the shell forked to start it, whose handlers are
# the shell's) and catches SIGTERM (bit 15 of SigCgt), or fails after 60 s.
wait_for_handlers() {
  local deadline=$((SECONDS + 60)) command mask
  while ((SECONDS < deadline)); do
    command=$(cat "/proc/$1/comm" 2>/dev/null) || return 0  # ended already
    mask=$(awk '/^SigCgt:/ { print $2 }' "/proc/$1/status" 2>/dev/null) || return 0
    [[ -n $mask ]] || return 0
    if [[ $command == dqskin ]] && (((16#$mask >> 14) & 1)); then return 0; fi
    sleep 0.01
  done
  fail "process $1 did not catch SIGTERM within 60 s"
}

# stop NAME SIGNAL DELAY COMMAND...: runs COMMAND (stderr in $scratch/NAME.stderr), sends SIGNAL DELAY
# seconds after its handlers are in place, and sets $status to its exit status (128 + N: signal N).
stop() {
  local name=$1 signal=$2 delay=$3
  shift 3
  "$@" >/dev/null 2>"$scratch/$name.stderr" &
  pid=$!
  trap 'kill -KILL "$pid" 2>/dev/null || true' EXIT  # a failing or timed-out test leaves nothing running
  wait_for_handlers "$pid"
  sleep "$delay"
  kill "-$signal" "$pid" 2>/dev/null || true  # it may have finished
  status=0
  wait "$pid" || status=$?
  trap - EXIT
}

# expect_stopped NAME COMMAND SIGNAL_NUMBER: the run ended by the signal, with the one line that says so.
expect_stopped() {
  local name=$1 command=$2 number=$3
  [[ $status == $((128 + number)) ]] || { cat "$scratch/$name.stderr"; fail "$name: exited $status, not $((128 + number))"; }
  [[ $(wc -l <"$scratch/$name.stderr") == 1 ]] || { cat "$scratch/$name.stderr"; fail "$name: not exactly one line on stderr"; }
  grep -q "^dqskin: $command stopped by signal $number; " "$scratch/$name.stderr" ||
    { cat "$scratch/$name.stderr"; fail "$name: the line does not say that $command was stopped by signal $number"; }
}

rm -rf "$scratch"
mkdir -p "$scratch"

big=$scratch/entries_400k
cp -a "$hostile/verify/entries_400k" "$big"
before=$(snapshot "$big")
stop merge_big TERM 0 "$dqskin" merge "$big"
expect_stopped merge_big merge 15
[[ $(snapshot "$big") == "$before" ]] || fail "merge_big: the stopped merge changed $big"
echo "merge of 400,000 files stopped: $(cat "$scratch/merge_big.stderr")"

stop verify_big INT 0.2 "$dqskin" verify "$big"
expect_stopped verify_big verify 2
echo "verify of 400,000 files stopped: $(cat "$scratch/verify_big.stderr")"

small=$scratch/mergeable
cp -a "$hostile/verify/mergeable" "$small"
before=$(snapshot "$small")
stopped=0
for delay in 0 0.02 0.05 0.1 0.2 0.4 0.8 1.6; do
  stop "merge_$delay" TERM "$delay" "$dqskin" merge "$small" --quiet
  # Exit 0, or the signal while the finished merge was ending: merged whole.
  if [[ $status == 0 || ($status == 143 && -f $small/manifest.json) ]]; then
    [[ -f $small/manifest.json ]] || fail "merge after $delay s: exited 0 without manifest.json"
    left=$(cd "$small" && find . -maxdepth 1 \( -name 'manifest.shard-*' -o -name '.*' \) ! -name .)
    [[ -z $left ]] || fail "merge after $delay s: merged, but left $left"
    echo "signal after $delay s: too late, merged whole (exit $status)"
    rm "$small/manifest.json"
    cp "$hostile/verify/mergeable/"manifest.shard-*.json "$small/"
    [[ $(snapshot "$small") == "$before" ]] || fail "the folder could not be put back after the merge"
    continue
  fi
  expect_stopped "merge_$delay" merge 15
  [[ $(snapshot "$small") == "$before" ]] || fail "merge after $delay s: the stopped merge changed $small"
  echo "signal after $delay s: stopped, folder as it was"
  stopped=$((stopped + 1))
done
((stopped > 0)) || fail "no merge of 10,000 files was stopped: the signals came too late to test anything"
rm -rf "$scratch"
