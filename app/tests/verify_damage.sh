#!/usr/bin/env bash
# What `dqskin verify` and `dqskin merge` find in damaged folders. A small bake of the bundled rig is
# copied and damaged five ways (a flipped byte, a truncated file, a missing file, an extra file, a leftover
# temporary): verify must exit 2 with exactly one line, naming that file, and --json must say ok false and
# the problem's kind; the undamaged folder must pass. Also: a manifest naming a path outside its folder
# (a FIFO there, which would block a reader), a folder without a manifest, a shard missing beside another
# of its job, a merge of shards run with different --mode, and `dqskin render` in 2 shards merged: its
# render-manifest.json byte-identical to the unsharded render's, and with --sheet listing both shards'
# sheets.
#
#   verify_damage.sh DQSKIN RIG SCRATCH
#     DQSKIN   the dqskin binary
#     RIG      testdata/bending_arm.gltf (one animation, "bend")
#     SCRATCH  a folder of this test's own (emptied first)
set -euo pipefail

dqskin=$1
rig=$2
scratch=$3

fail() {
  echo "FAIL: $*"
  exit 1
}

# expect_status STATUS NAME COMMAND [ARG...]: runs COMMAND with its stdout in $scratch/NAME.stdout and its
# stderr in $scratch/NAME.stderr; fails unless it exits STATUS.
expect_status() {
  local expected=$1 name=$2 status=0
  shift 2
  "$@" >"$scratch/$name.stdout" 2>"$scratch/$name.stderr" || status=$?
  if [[ $status != "$expected" ]]; then
    sed "s/^/  $name stdout: /" "$scratch/$name.stdout"
    sed "s/^/  $name stderr: /" "$scratch/$name.stderr"
    fail "$name: exited $status, not $expected: $*"
  fi
}

rm -rf "$scratch"
mkdir -p "$scratch"
clean=$scratch/clean
expect_status 0 bake "$dqskin" bake "$rig" -o "$clean" --frames 0:5 --format glb,vat --quiet
expect_status 0 verify_clean "$dqskin" verify "$clean"
[[ ! -s "$scratch/verify_clean.stdout" ]] || fail "verify of the undamaged folder printed problems"
expect_status 0 verify_clean_json "$dqskin" verify "$clean" --json --quiet
grep -q '"ok": true' "$scratch/verify_clean_json.stdout" || fail "verify --json of the undamaged folder: no \"ok\": true"

clip=bending_arm/bend
frame=$clip/frame_0002.glb

# damage NAME KIND FILE COMMAND...: a copy of the clean folder, COMMAND run in it, then verify must exit 2
# with one line naming FILE, and --json must say ok false with one problem of KIND for FILE.
damage() {
  local name=$1 kind=$2 file=$3
  shift 3
  local copy=$scratch/$name
  cp -a "$clean" "$copy"
  (cd "$copy" && "$@")
  expect_status 2 "$name" "$dqskin" verify "$copy" --quiet
  local lines
  lines=$(wc -l <"$scratch/$name.stdout")
  [[ $lines == 1 ]] || { cat "$scratch/$name.stdout"; fail "$name: verify printed $lines lines, not 1"; }
  grep -qF "$copy/$file: " "$scratch/$name.stdout" || { cat "$scratch/$name.stdout"; fail "$name: verify did not name $file"; }
  expect_status 2 "${name}_json" "$dqskin" verify "$copy" --json --quiet
  local json=$scratch/${name}_json.stdout
  grep -q '"ok": false' "$json" || fail "$name: verify --json: no \"ok\": false"
  [[ $(grep -c '"kind":' "$json") == 1 ]] || fail "$name: verify --json: not exactly one problem"
  grep -q "\"kind\": \"$kind\"" "$json" || { cat "$json"; fail "$name: verify --json: the kind is not $kind"; }
  grep -qF "\"path\": \"$file\"" "$json" || { cat "$json"; fail "$name: verify --json: the path is not $file"; }
  echo "$name: $(cat "$scratch/$name.stdout")"
}

flip_byte() {  # flip_byte FILE OFFSET: the byte at OFFSET inverted
  local byte
  byte=$(od -An -tu1 -j "$2" -N 1 "$1" | tr -d ' ')
  printf "\\$(printf '%03o' $((byte ^ 255)))" | dd of="$1" bs=1 seek="$2" conv=notrunc status=none
}

damage flipped_byte hash "$frame" flip_byte "$frame" 100
damage truncated size "$frame" truncate -s -10 "$frame"
damage missing missing "$frame" rm "$frame"
damage extra unlisted "$clip/extra.txt" sh -c "echo extra > $clip/extra.txt"
damage temporary temporary "$clip/.frame_0004.glb.tmp-4242-0" sh -c "echo partial > $clip/.frame_0004.glb.tmp-4242-0"

# A manifest whose output path leaves the folder: a problem, and the path not opened (a FIFO there would
# block the reader until the timeout).
escape=$scratch/escape
mkdir -p "$escape"
cp -a "$clean" "$escape/out"
mkfifo "$escape/outside"
sed -i "s#\"path\": \"$frame\"#\"path\": \"../outside\"#" "$escape/out/manifest.json"
grep -q '"path": "../outside"' "$escape/out/manifest.json" || fail "the manifest was not edited"
expect_status 2 escape timeout 30 "$dqskin" verify "$escape/out" --quiet
[[ $(wc -l <"$scratch/escape.stdout") == 1 ]] || { cat "$scratch/escape.stdout"; fail "escape: not one problem line"; }
grep -q "outside the folder" "$scratch/escape.stdout" || { cat "$scratch/escape.stdout"; fail "escape: no 'outside the folder'"; }
echo "escape: $(cat "$scratch/escape.stdout")"

# A folder with no manifest is not a bake or render folder.
mkdir -p "$scratch/empty"
expect_status 2 no_manifest "$dqskin" verify "$scratch/empty" --quiet
grep -q "no manifest" "$scratch/no_manifest.stdout" || { cat "$scratch/no_manifest.stdout"; fail "no_manifest: no 'no manifest'"; }

# A shard that has not finished while another of its job has.
half=$scratch/half
expect_status 0 half_shard0 "$dqskin" bake "$rig" -o "$half" --frames 0:5 --quiet --shard 0/2
expect_status 2 half_verify "$dqskin" verify "$half" --quiet
[[ $(wc -l <"$scratch/half_verify.stdout") == 1 ]] || { cat "$scratch/half_verify.stdout"; fail "half_verify: not one line"; }
grep -qF "$half/manifest.shard-1-of-2.json: missing" "$scratch/half_verify.stdout" ||
  { cat "$scratch/half_verify.stdout"; fail "half_verify: shard 1 of 2 not named as missing"; }
expect_status 2 half_verify_json "$dqskin" verify "$half" --json --quiet
grep -q '"kind": "shard-missing"' "$scratch/half_verify_json.stdout" || fail "half_verify: --json kind is not shard-missing"
echo "half_verify: $(cat "$scratch/half_verify.stdout")"

# Shards run with different flags are not merged.
mixed=$scratch/mixed
expect_status 0 mixed_shard0 "$dqskin" bake "$rig" -o "$mixed" --frames 0:5 --quiet --shard 0/2
expect_status 0 mixed_shard1 "$dqskin" bake "$rig" -o "$mixed" --frames 0:5 --quiet --shard 1/2 --mode lbs
expect_status 2 mixed_merge "$dqskin" merge "$mixed"
grep -q 'manifest\.shard-1-of-2\.json: .*mode' "$scratch/mixed_merge.stderr" ||
  { cat "$scratch/mixed_merge.stderr"; fail "mixed_merge: shard 1 and the key mode not named"; }
[[ ! -e "$mixed/manifest.json" ]] || fail "mixed_merge: manifest.json written"
[[ -e "$mixed/manifest.shard-0-of-2.json" && -e "$mixed/manifest.shard-1-of-2.json" ]] ||
  fail "mixed_merge: the refused merge removed a shard manifest"
echo "mixed_merge: $(head -n 1 "$scratch/mixed_merge.stderr")"

# render: 2 shards merged equal the unsharded render, manifest included; with --sheet both shards' sheets.
render=(render "$rig" --size 32x32 --frames 0:5 --quiet)
for i in 0 1; do
  expect_status 0 render_shard$i "$dqskin" "${render[@]}" -o "$scratch/render" --shard $i/2
  expect_status 0 sheet_shard$i "$dqskin" "${render[@]}" -o "$scratch/sheet" --shard $i/2 --sheet
done
expect_status 0 render_merge "$dqskin" merge "$scratch/render"
expect_status 0 render_whole "$dqskin" "${render[@]}" -o "$scratch/render_whole"
cmp "$scratch/render/render-manifest.json" "$scratch/render_whole/render-manifest.json" ||
  fail "the merged render-manifest.json differs from the unsharded render's"
diff -r "$scratch/render" "$scratch/render_whole" || fail "the merged render differs from the unsharded one (above)"
expect_status 0 sheet_merge "$dqskin" merge "$scratch/sheet"
for i in 0 1; do
  grep -qF "\"path\": \"$clip/sheet_shard${i}of2.png\"" "$scratch/sheet/render-manifest.json" ||
    fail "the merged render-manifest.json does not list $clip/sheet_shard${i}of2.png"
done
expect_status 0 sheet_verify "$dqskin" verify "$scratch/sheet"
echo "render: 2 shards merged equal the unsharded render; with --sheet both shards' sheets are listed"
