#!/usr/bin/env bash
# A shard killed mid-run (kill -9) and run again: shard 0 of 4 of a BrainStem bake is killed while it has
# finished files and temporaries (.NAME.tmp-PID-N) on disk, and shards 1..3 run to the end (leaving shard
# 0's files alone). Then
# `dqskin merge` must refuse (exit 2, naming manifest.shard-0-of-4.json as missing) and write no
# manifest.json; shard 0 run again must keep the files its killed run finished (same inode and time
# stamp) and remove its temporaries; `dqskin merge` and `dqskin verify` must then succeed and the folder
# must equal an unsharded bake byte for byte. Exits 77 (CTest's skip) with the reason when the shared
# sample model is absent.
#
#   kill_shard.sh DQSKIN SHARED_TESTDATA SCRATCH
#     DQSKIN           the dqskin binary
#     SHARED_TESTDATA  the shared sample models (BrainStem/BrainStem.glb)
#     SCRATCH          a folder of this test's own (emptied first; its bakes are deleted when the test passes)
set -euo pipefail

dqskin=$1
model=$2/BrainStem/BrainStem.glb
scratch=$3

fail() {
  echo "FAIL: $*"
  exit 1
}

if [[ ! -f "$model" ]]; then
  echo "skipped: the shared sample model $model is absent"
  exit 77
fi

# Shard 0 is the one killed: the shards deal the work by cost (docs/DESIGN.md §6.5), and shard 0 gets the
# morph animation, which cannot be cut (all 100 frames deformed, encoded and checked), with glb frames;
# it runs for seconds with large temporaries open, while shards 1..3 bake their slices of the textures.
# 100 frames at 10 fps keep the four folders' bytes to a few hundred MB.
flags=(--format glb,vat,bones,morph --fps 10 --frames 0:99 --quiet)
out=$scratch/out
whole=$scratch/whole
rm -rf "$scratch"
mkdir -p "$scratch"

# Shard 0 runs first, so that every frame in the folder is its own. Builtins only (compgen -G), so that
# the polling does not take the cores the shard runs on.
has_finished_frame() { compgen -G "$out/BrainStem/*/frame_*.glb" >/dev/null; }
has_temporary() { compgen -G "$out/BrainStem/*/.*.tmp-*" >/dev/null; }

"$dqskin" bake "$model" -o "$out" "${flags[@]}" --shard 0/4 2>/dev/null &
pid=$!
trap 'kill -KILL "$pid" 2>/dev/null || true' EXIT  # a failing or timed-out test leaves no shard running
# The shard is stopped (SIGSTOP) before the folder is looked at, so that the kill lands in the state that
# was seen: a finished frame and a temporary on disk. If the temporary has just been renamed, it runs on.
killed=0
deadline=$((SECONDS + 120))
while ((SECONDS < deadline)); do
  if [[ -e "$out/manifest.shard-0-of-4.json" ]]; then
    fail "shard 0/4 finished before it could be killed: the kill came too late and would test nothing"
  fi
  if has_finished_frame && has_temporary; then
    kill -STOP "$pid"
    if has_temporary && [[ ! -e "$out/manifest.shard-0-of-4.json" ]]; then
      kill -KILL "$pid"
      killed=1
      break
    fi
    kill -CONT "$pid"
  fi
  sleep 0.02
done
if [[ $killed == 0 ]]; then
  kill -KILL "$pid" 2>/dev/null || true
  fail "shard 0/4 never had a finished frame and a temporary on disk within 120 s"
fi
status=0
wait "$pid" || status=$?
trap - EXIT
[[ $status == 137 ]] || fail "the killed shard exited $status, not 137 (SIGKILL)"
[[ ! -e "$out/manifest.shard-0-of-4.json" ]] || fail "the killed shard wrote its manifest"

mapfile -t temporaries < <(find "$out" -name '.*.tmp-*' | sort)
mapfile -t finished < <(find "$out" -name 'frame_*.glb' | sort)
echo "killed shard 0/4 with ${#finished[@]} frames finished and these temporaries on disk:"
printf '  %s\n' "${temporaries[@]#"$out/"}"
((${#temporaries[@]} > 0)) || fail "the killed shard left no temporary"
((${#finished[@]} > 0)) || fail "the killed shard finished no frame"
kept=${finished[0]}
kept_before=$(stat -c '%i %y' "$kept")

# The other shards run meanwhile (as they would in parallel): they must leave shard 0's files alone.
for i in 1 2 3; do
  "$dqskin" bake "$model" -o "$out" "${flags[@]}" --shard "$i/4" 2>/dev/null || fail "shard $i/4 exited $?"
done
for temporary in "${temporaries[@]}"; do
  [[ -e "$temporary" ]] || fail "another shard removed shard 0's temporary ${temporary#"$out/"}"
done

status=0
"$dqskin" merge "$out" 2>"$scratch/merge.stderr" || status=$?
echo "dqskin merge of the folder with shard 0 killed (exit $status):"
sed 's/^/  /' "$scratch/merge.stderr"
[[ $status == 2 ]] || fail "dqskin merge exited $status, not 2"
grep -q "manifest\.shard-0-of-4\.json: missing" "$scratch/merge.stderr" ||
  fail "dqskin merge did not name manifest.shard-0-of-4.json as missing"
[[ ! -e "$out/manifest.json" ]] || fail "the refused merge wrote manifest.json"
status=0
"$dqskin" verify "$out" --quiet >"$scratch/verify.stdout" || status=$?
[[ $status == 2 ]] || fail "dqskin verify of the folder with shard 0 killed exited $status, not 2"
grep -q "manifest\.shard-0-of-4\.json: missing" "$scratch/verify.stdout" ||
  fail "dqskin verify did not name manifest.shard-0-of-4.json as missing"
for temporary in "${temporaries[@]}"; do
  grep -qF "$temporary" "$scratch/verify.stdout" || fail "dqskin verify did not name $temporary"
done

"$dqskin" bake "$model" -o "$out" "${flags[@]}" --shard 0/4 2>/dev/null || fail "shard 0/4 run again exited $?"
left=$(find "$out" -name '.*.tmp-*')
[[ -z "$left" ]] || fail "temporaries left after shard 0/4 ran again: $left"
[[ "$(stat -c '%i %y' "$kept")" == "$kept_before" ]] ||
  fail "shard 0/4 run again rewrote ${kept#"$out/"}, which its killed run had finished"

"$dqskin" merge "$out" || fail "dqskin merge exited $? after shard 0/4 ran again"
"$dqskin" verify "$out" || fail "dqskin verify exited $? after the merge"
"$dqskin" bake "$model" -o "$whole" "${flags[@]}" 2>/dev/null || fail "the unsharded bake exited $?"
diff -r "$out" "$whole" || fail "the merged shards differ from the unsharded bake (above)"
echo "killed and rerun shard merged equals the unsharded bake: $(find "$out" -type f | wc -l) files"
rm -rf "$out" "$whole"
