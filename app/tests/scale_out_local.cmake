# Scale-out on one machine, end to end: the GNU parallel recipe of docs/commands/bake.md, a shard killed mid-run and run
# again, and what `dqskin verify` and `dqskin merge` find in damaged or mismatched folders. Each script
# empties a scratch folder of its own first, so the tests need no fixture and may run at once. The two
# that bake shared sample models skip (exit 77) with the reason when the models or GNU parallel are absent.
# verify_damage renders, so it makes a GL context (label gpu); the bakes deform on the default backend.
set(scale_out_scratch ${CMAKE_CURRENT_BINARY_DIR}/scale_out)
set(scale_out_shared_testdata ${PROJECT_SOURCE_DIR}/../shared/testdata)

add_test(NAME cli.scale_out_parallel_recipe COMMAND bash ${PROJECT_SOURCE_DIR}/app/tests/parallel_recipe.sh
  $<TARGET_FILE:dqskin_cli> ${PROJECT_SOURCE_DIR}/docs/commands/bake.md ${scale_out_shared_testdata} ${scale_out_scratch}/parallel_recipe)
add_test(NAME cli.scale_out_kill_shard COMMAND bash ${PROJECT_SOURCE_DIR}/app/tests/kill_shard.sh
  $<TARGET_FILE:dqskin_cli> ${scale_out_shared_testdata} ${scale_out_scratch}/kill_shard)
set_tests_properties(cli.scale_out_parallel_recipe cli.scale_out_kill_shard PROPERTIES
  SKIP_RETURN_CODE 77 TIMEOUT 300 ENVIRONMENT "${bake_test_environment}")

add_test(NAME cli.scale_out_verify_damage COMMAND bash ${PROJECT_SOURCE_DIR}/app/tests/verify_damage.sh
  $<TARGET_FILE:dqskin_cli> ${PROJECT_SOURCE_DIR}/testdata/bending_arm.gltf ${scale_out_scratch}/verify_damage)
set_tests_properties(cli.scale_out_verify_damage PROPERTIES TIMEOUT 300 ENVIRONMENT "${bake_test_environment}" LABELS gpu)
