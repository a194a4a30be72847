#!/usr/bin/env bash
# The Slurm recipe of docs/commands/bake.md ("Sharding"), run as written on a one-node Slurm cluster of this machine: an
# array job of 32 shards bakes shared models into one folder, `dqskin merge` joins the shards' manifests,
# and the folder must equal an unsharded bake of the same models byte for byte (names and contents).
#
#   slurm_recipe.sh DQSKIN SLURM_CLUSTER_SH SHARED_TESTDATA SCRATCH
#
# DQSKIN is the binary (named dqskin: the recipe calls it by name, found on PATH), SLURM_CLUSTER_SH the
# script that starts and stops the cluster, SCRATCH a folder this test empties and owns. Exit status 77
# (CTest's skip), with the reason printed, when the shared models are absent or the cluster cannot run
# here. SLURM_RECIPE_TIMEOUT (default 420) bounds the wait for the array job in seconds.
set -euo pipefail

dqskin=$1
cluster=$2
testdata=$3
scratch=$4
timeout=${SLURM_RECIPE_TIMEOUT:-420}

skip() {
  echo "slurm_recipe: SKIPPED: $*"
  exit 77
}
fail() {
  echo "slurm_recipe: FAILED: $*"
  exit 1
}

# Four skinned models, six animations, 322 frames: enough for every one of the 32 shards to get work, and
# the whole test stays within a minute on two cores.
models=(Fox CesiumMan RiggedSimple RiggedFigure)
for m in "${models[@]}"; do
  [ -f "$testdata/$m/$m.glb" ] || skip "$testdata/$m/$m.glb not found (the shared test models)"
done

# A cluster an earlier run left (killed by CTest's timeout, which the trap below cannot see) is stopped first.
[ -d "$scratch/cluster" ] && bash "$cluster" stop "$scratch/cluster"
rm -rf "$scratch"
mkdir -p "$scratch/models" "$scratch/logs"
for m in "${models[@]}"; do ln -s "$testdata/$m/$m.glb" "$scratch/models/$m.glb"; done

# The cluster is stopped however the test ends.
trap 'bash "$cluster" stop "$scratch/cluster" || echo "slurm_recipe: the cluster did not stop cleanly"' EXIT
status=0
started=$(bash "$cluster" start "$scratch/cluster" 2>&1) || status=$?
case $status in
  0) ;;
  77) skip "no Slurm cluster here: $(tail -n 1 <<<"$started")" ;;
  *) fail "scripts/check/slurm_cluster.sh start exited with $status: $started" ;;
esac
# This cluster's configuration, and none of the caller's sbatch defaults (SBATCH_PARTITION and the like).
# shellcheck disable=SC2046
unset SLURM_CONF $(compgen -v SBATCH_ || true)
eval "$(grep '^export SLURM_CONF=' <<<"$started")"
[ -n "${SLURM_CONF:-}" ] || fail "scripts/check/slurm_cluster.sh start printed no SLURM_CONF: $started"

# The recipe's line as the page has it, run where models/ is (sbatch's default working folder is the
# submitting one); --output puts each shard's messages where a failure below can show them.
cd "$scratch"
PATH="$(dirname "$dqskin"):$PATH"
export PATH
# Submits an array job of TASKS tasks running COMMAND (its messages in logs/NAME-<task>.out), waits until
# it is done and fails unless every task completed with exit code 0.
run_array() {  # NAME TASKS COMMAND
  local name=$1 tasks=$2 command=$3 submitted job started_at records tasks_ok
  submitted=$(sbatch --output="$scratch/logs/$name-%a.out" --array=0-$((tasks - 1)) --wrap "$command")
  echo "$submitted"
  job=${submitted##* }
  [[ "$job" =~ ^[0-9]+$ ]] || fail "sbatch printed no job id: $submitted"
  started_at=$SECONDS
  while [ -n "$(squeue -h -j "$job" 2>/dev/null)" ]; do
    if ((SECONDS - started_at > timeout)); then
      squeue -j "$job" || true
      scancel "$job" || true
      fail "array job $job not done after $timeout s"
    fi
    sleep 2
  done
  echo "array job $job ($name) done in $((SECONDS - started_at)) s"
  # The controller keeps finished jobs' records for a while (MinJobAge, 300 s by default): every task must
  # have completed with exit code 0.
  records=$(scontrol -o show job "$job")
  tasks_ok=$(grep -c 'JobState=COMPLETED .*ExitCode=0:0' <<<"$records" || true)
  if [ "$tasks_ok" -ne "$tasks" ]; then
    grep -o 'ArrayTaskId=[0-9]* .*JobState=[A-Z_]* .*ExitCode=[0-9:]*' <<<"$records" |
      sed 's/ .*JobState=/ JobState=/; s/ Reason.*ExitCode=/ ExitCode=/' | grep -v 'JobState=COMPLETED ExitCode=0:0$' || true
    for f in "$scratch"/logs/"$name"-*.out; do
      [ -s "$f" ] && { echo "== $f"; cat "$f"; }
    done
    fail "$tasks_ok of $tasks shards completed with exit code 0"
  fi
}

# shellcheck disable=SC2016  # $SLURM_ARRAY_TASK_ID is the job's to expand
run_array shard 32 'dqskin bake models/*.glb -o out --shard $SLURM_ARRAY_TASK_ID/32 --quiet'
"$dqskin" merge out || fail "dqskin merge out exited with $?"
dqskin bake models/*.glb -o unsharded --quiet || fail "the unsharded bake exited with $?"
diff -r out unsharded || fail "the merged shards differ from the unsharded bake"
echo "slurm_recipe: 32 shards merged equal the unsharded bake: $(find out -type f | wc -l) files"

# One long clip in every texture format, 8 tasks: the textures are cut into slices that the shards write
# as pieces of rows (docs/DESIGN.md §6.5), which the merge splices into the unsharded bake's files.
textures='--format glb,vat,bones,morph'
# shellcheck disable=SC2016
run_array textures 8 "dqskin bake models/CesiumMan.glb -o textures $textures --shard \$SLURM_ARRAY_TASK_ID/8 --quiet"
pieces=$(find textures -name '*.exr.rows-*' | wc -l)
[ "$pieces" -ge 4 ] || fail "the 8 shards wrote $pieces pieces of texture rows, expected the textures cut in two slices at least"
"$dqskin" merge textures || fail "dqskin merge textures exited with $?"
# shellcheck disable=SC2086
dqskin bake models/CesiumMan.glb -o textures_unsharded $textures --quiet || fail "the unsharded texture bake exited with $?"
diff -r textures textures_unsharded || fail "the merged texture shards differ from the unsharded bake"
echo "slurm_recipe: 8 shards of one clip's textures ($pieces pieces) merged equal the unsharded bake: $(find textures -type f | wc -l) files"
