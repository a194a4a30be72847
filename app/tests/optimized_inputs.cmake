# Real optimizer outputs read by every command: CesiumMan (textured, skinned, animated) through gltfpack
# (KHR_mesh_quantization and KHR_texture_transform by default, EXT_meshopt_compression with -c) and
# glTF-Transform (optimize: meshopt, quantization; draco: KHR_draco_mesh_compression), each made at test time
# with the npm tools that scripts/install/node_tools.sh puts into the build folder's tools/ (skipped when
# absent), then info, bake and render of it, and its render compared with the original's
# (optimized_input_case.cmake).
set(_model ${PROJECT_SOURCE_DIR}/../shared/testdata/CesiumMan/CesiumMan.glb)
function(dqskin_optimized_input name tool)
  add_test(NAME cli.optimized_input_${name}
    COMMAND ${CMAKE_COMMAND} -DDQSKIN=$<TARGET_FILE:dqskin_cli> -DWORK=${CMAKE_CURRENT_BINARY_DIR}/optimized_input/${name}
            -DA=${_model} -DTOOL=${tool} -DTOOLS=${CMAKE_BINARY_DIR}/tools/node_modules/.bin "-DTOOL_ARGS=${ARGN}"  # quoted: one argument
            -DFRAME=10 -P ${PROJECT_SOURCE_DIR}/app/tests/optimized_input_case.cmake)
  set_tests_properties(cli.optimized_input_${name} PROPERTIES SKIP_REGULAR_EXPRESSION "optimized_input: SKIPPED"
                       TIMEOUT 600 LABELS "gpu;optimized_input" ENVIRONMENT "${bake_test_environment}")
endfunction()
dqskin_optimized_input(gltfpack_default gltfpack -i <A> -o <B>)
dqskin_optimized_input(gltfpack_meshopt gltfpack -i <A> -o <B> -c)
dqskin_optimized_input(gltf_transform_optimize gltf-transform optimize <A> <B>)
dqskin_optimized_input(gltf_transform_draco gltf-transform draco <A> <B>)
