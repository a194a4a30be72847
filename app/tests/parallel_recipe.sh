#!/usr/bin/env bash
# The GNU parallel recipe of docs/commands/bake.md ("Sharding"), run as written: 8 shards of a bake of a
# models/ folder on one machine, then `dqskin merge out`; the folder must equal an unsharded bake of the
# same models byte for byte (manifest.json included) and `dqskin verify out` must find nothing wrong. The
# recipe line is read from that page, so the test runs what the page says. Exits 77 (CTest's skip) with the reason when GNU
# parallel or the shared sample models are absent.
#
#   parallel_recipe.sh DQSKIN PAGE SHARED_TESTDATA SCRATCH
#     DQSKIN           the dqskin binary
#     PAGE             the page holding the recipe (one line starting "parallel dqskin bake ")
#     SHARED_TESTDATA  the shared sample models (Fox/Fox.glb, ...)
#     SCRATCH          a folder of this test's own (emptied first)
set -euo pipefail

dqskin=$1
page=$2
shared=$3
scratch=$4
models=(Fox/Fox.glb CesiumMan/CesiumMan.glb RiggedSimple/RiggedSimple.glb RiggedFigure/RiggedFigure.glb)

fail() {
  echo "FAIL: $*"
  exit 1
}

if ! parallel --version 2>/dev/null | grep -q '^GNU parallel'; then
  echo "skipped: GNU parallel is not installed (Debian: apt-get install parallel)"
  exit 77
fi
for model in "${models[@]}"; do
  if [[ ! -f "$shared/$model" ]]; then
    echo "skipped: the shared sample model $shared/$model is absent"
    exit 77
  fi
done

mapfile -t recipes < <(grep -E '^parallel dqskin bake ' "$page" || true)
[[ ${#recipes[@]} == 1 ]] || fail "expected one line starting 'parallel dqskin bake ' in $page, found ${#recipes[@]}"
recipe=${recipes[0]}
echo "recipe: $recipe"

rm -rf "$scratch"
mkdir -p "$scratch/models" "$scratch/bin" "$scratch/home/.parallel"
for model in "${models[@]}"; do
  ln -s "$shared/$model" "$scratch/models/"
done
# The recipe calls `dqskin` by name.
ln -s "$dqskin" "$scratch/bin/dqskin"
export PATH="$scratch/bin:$PATH"
# GNU parallel writes under ~/.parallel and, on a terminal, asks once per user to cite it. A HOME of the
# test's own keeps the real one untouched, and will-cite there answers the question without changing the
# recipe's command line (which --will-cite would).
export HOME="$scratch/home"
touch "$HOME/.parallel/will-cite"

cd "$scratch"
bash -c "$recipe" || fail "the recipe exited $?"
for i in $(seq 0 7); do
  [[ -f out/manifest.shard-$i-of-8.json ]] || fail "shard $i wrote no out/manifest.shard-$i-of-8.json"
done
[[ ! -e out/manifest.json ]] || fail "a shard wrote out/manifest.json"

dqskin merge out || fail "dqskin merge out exited $?"
[[ -f out/manifest.json ]] || fail "dqskin merge wrote no out/manifest.json"
shards_left=$(find out -maxdepth 1 -name 'manifest.shard-*' | wc -l)
[[ $shards_left == 0 ]] || fail "dqskin merge left $shards_left shard manifests"

dqskin bake models/*.glb -o whole --quiet || fail "the unsharded bake exited $?"
diff -r out whole || fail "the merged shards differ from the unsharded bake (above)"
dqskin verify out || fail "dqskin verify out exited $?"
echo "8 shards merged equal the unsharded bake: $(find out -type f | wc -l) files"

# The recipe with every texture format and the morph animation: the textures are cut into slices that the
# shards write as pieces of rows (docs/DESIGN.md §6.5), which the merge splices.
textures="--format glb,vat,bones,morph"
recipe_textures=${recipe/ -o out / -o textures $textures }
[[ $recipe_textures != "$recipe" ]] || fail "the recipe has no ' -o out ' to add the formats to"
bash -c "$recipe_textures" || fail "the recipe with $textures exited $?"
pieces=$(find textures -name '*.exr.rows-*' | wc -l)
(( pieces >= 4 )) || fail "the 8 shards wrote $pieces pieces of texture rows, expected a texture cut in two slices at least"
dqskin verify textures || fail "dqskin verify of the unmerged shards exited $?"
dqskin merge textures || fail "dqskin merge textures exited $?"
[[ -z $(find textures -name '*.exr.rows-*' -o -name '*.template') ]] || fail "dqskin merge left pieces behind"
# shellcheck disable=SC2086
dqskin bake models/*.glb -o textures_whole $textures --quiet || fail "the unsharded bake with $textures exited $?"
diff -r textures textures_whole || fail "the merged texture shards differ from the unsharded bake (above)"
echo "8 shards with $pieces pieces of texture rows merged equal the unsharded bake: $(find textures -type f | wc -l) files"
