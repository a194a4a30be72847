#!/usr/bin/env bash
# A report is one output: all of its files or none of them (docs/SECURITY.md "Every command").
#  1. SIGTERM as the first contact sheet is being written: the report is still to write report.json
#     (tens of MB for 300 joints) and report.html, longer than the quarter of a second a stopped process
#     is given. The process must die of the signal with one line, leaving no temporary and either all of
#     the input's report files or none (it left the sheet, and report.json, without report.html).
#  2. A run killed with SIGKILL leaves its temporaries (".NAME.tmp-PID-N"); the next run of the same
#     report must remove them (they stayed for ever).
#
#   report_signal.sh DQSKIN INPUT SCRATCH
#     DQSKIN   the dqskin binary
#     INPUT    a rig whose report takes seconds and writes large files (scripts/testdata/make_hostile_commands.py)
#     SCRATCH  a folder of this test's own (emptied first)
set -euo pipefail

dqskin=$1
input=$2
scratch=$3
stem=$(basename "${input%.*}")
out=$scratch/out
folder=$out/$stem

fail() {
  echo "FAIL: $*"
  exit 1
}

report_files() { find "$folder" -maxdepth 1 -type f \( -name 'worst_*.png' -o -name report.json -o -name report.html \) 2>/dev/null | sort; }
temporaries() { find "$out" -name '.*.tmp-*' -o -name '.*.old-*' 2>/dev/null; }

rm -rf "$scratch"
mkdir -p "$scratch"

# ---- 1: SIGTERM while the sheet is written ------------------------------------------------------------------
"$dqskin" report "$input" -o "$out" --fps 120 --quiet 2>"$scratch/stderr" &
pid=$!
deadline=$((SECONDS + 300))
until compgen -G "$folder/.worst_*.tmp-*" >/dev/null || compgen -G "$folder/worst_*.png" >/dev/null; do
  kill -0 "$pid" 2>/dev/null || fail "the report ended before it wrote a contact sheet"
  ((SECONDS < deadline)) || { kill -9 "$pid"; fail "no contact sheet in 300 s"; }
  sleep 0.005
done
kill -TERM "$pid"
status=0
wait "$pid" || status=$?
echo "report stopped with status $status; left: $(report_files | tr '\n' ' ')"
cat "$scratch/stderr"
if ((status == 0)); then
  echo "note: the report had finished when the signal arrived"
else
  ((status == 143)) || fail "status $status, not death by SIGTERM (143)"
  [[ $(wc -l <"$scratch/stderr") -eq 1 ]] || fail "stderr is not one line"
  grep -q "stopped by signal 15" "$scratch/stderr" || fail "stderr does not say the report was stopped"
fi
[[ -z $(temporaries) ]] || fail "temporaries left: $(temporaries)"
count=$(report_files | wc -l)
((count == 0 || count == 3)) || fail "a partial report: $(report_files | tr '\n' ' ')"

# ---- 2: the leftovers of a killed run are removed by the next ------------------------------------------
mkdir -p "$folder"
# What SIGKILL leaves: a temporary of a process that no longer exists, beside each file the report writes.
for name in report.json report.html worst_bend_twist.png; do
  echo "partial" >"$folder/.$name.tmp-4194303-7"
done
"$dqskin" report "$input" -o "$out" --fps 10 --quiet || fail "the rerun failed"
[[ -z $(temporaries) ]] || fail "the rerun kept the killed run's temporaries: $(temporaries)"
[[ $(report_files | wc -l) -eq 3 ]] || fail "the rerun did not write the whole report: $(report_files | tr '\n' ' ')"
rm -rf "$scratch"
echo "PASS"
