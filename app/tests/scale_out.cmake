# The scale-out recipes of docs/commands/bake.md ("Sharding") run as written. The Slurm recipe starts a one-node Slurm cluster of this
# machine (scripts/check/slurm_cluster.sh) and bakes the shared models in 32 shards: minutes of every core, so
# it has a label of its own, left out of the release and sanitize presets and run by `ctest --preset slurm`
# (scripts/test.sh does). It skips (77) with the reason when the cluster cannot run here or the shared
# models are absent; it runs alone because the cluster's ports are fixed.
add_test(NAME cli.scale_out_slurm_recipe COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/slurm_recipe.sh
  $<TARGET_FILE:dqskin_cli> ${PROJECT_SOURCE_DIR}/scripts/check/slurm_cluster.sh ${PROJECT_SOURCE_DIR}/../shared/testdata
  ${CMAKE_CURRENT_BINARY_DIR}/slurm_recipe)
set_tests_properties(cli.scale_out_slurm_recipe PROPERTIES LABELS slurm SKIP_RETURN_CODE 77 TIMEOUT 600 RUN_SERIAL TRUE
  ENVIRONMENT "${bake_test_environment}")
