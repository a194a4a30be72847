# `dqskin optimize` (docs/commands/optimize.md) against the tools CI already trusts: each output passes
# `dqskin diff IN OUT --fail BUDGET` (the geometric diff, at its own times and correspondence), lints with
# no finding its input did not have and is valid glTF for the Khronos validator; bad budgets and inputs
# are one line, exit status 2, nothing written.
find_program(DQSKIN_NODE node)
set(_optimize_dir ${CMAKE_CURRENT_BINARY_DIR}/optimize_out)
# Bundled rigs and shared models (the latter skip, with a line, without ../shared/testdata).
foreach(model twisted_cylinder.gltf walk_run_legs.gltf morph_skin.gltf interpolation_modes.gltf
              shared:CesiumMan/CesiumMan.glb shared:Fox/Fox.glb shared:RiggedFigure/RiggedFigure.glb
              shared:RiggedSimple/RiggedSimple.glb shared:AnimatedMorphCube/AnimatedMorphCube.glb
              shared:InterpolationTest/InterpolationTest.glb)
  if(model MATCHES "^shared:(.*)$")
    set(input ${PROJECT_SOURCE_DIR}/../shared/testdata/${CMAKE_MATCH_1})
  else()
    set(input ${PROJECT_SOURCE_DIR}/testdata/${model})
  endif()
  get_filename_component(stem ${input} NAME_WE)
  add_test(NAME cli.optimize_${stem} COMMAND ${CMAKE_COMMAND} -DDQSKIN=$<TARGET_FILE:dqskin_cli> -DINPUT=${input}
    -DOUT=${_optimize_dir}/${stem}.glb -DNODE=${DQSKIN_NODE} -DVALIDATOR=${CMAKE_BINARY_DIR}/tools/node_modules/gltf-validator
    -DSCRIPTS=${PROJECT_SOURCE_DIR}/scripts -P ${CMAKE_CURRENT_SOURCE_DIR}/tests/optimize_case.cmake)
  set_tests_properties(cli.optimize_${stem} PROPERTIES SKIP_REGULAR_EXPRESSION "optimize_case: SKIPPED" TIMEOUT 300)
endforeach()

# Bad input: one line "dqskin: …", exit status 2, no output.
set(_rig ${PROJECT_SOURCE_DIR}/testdata/bending_arm.gltf)
foreach(case "negative_budget|${_rig},-o,${_optimize_dir}/bad.glb,--max-error,-0.5|--max-error '-0.5' is not a length"
             "nan_budget|${_rig},-o,${_optimize_dir}/bad.glb,--max-error,nan|--max-error 'nan' is not a length"
             "not_glb|${_rig},-o,${_optimize_dir}/bad.gltf,--max-error,0.01|-o must name a .glb file"
             "dib|${_rig},-o,${_optimize_dir}/bad.glb,--max-error,0.01,--mode,dib|--mode 'dib' is not one of lbs, dqs"
             "no_animation|STILL,-o,${_optimize_dir}/bad.glb,--max-error,0.01|[^\n]*has no animation to optimize"
             "unwritable|${_rig},-o,/nonexistent-folder/out.glb,--max-error,0.01|[^\n]*/nonexistent-folder/out.glb")
  string(REPLACE "|" ";" parts "${case}")
  list(GET parts 0 name)
  list(GET parts 1 args)  # comma-separated: a CTest argument cannot carry a list
  list(GET parts 2 regex)
  add_test(NAME cli.optimize_refuses_${name} COMMAND ${CMAKE_COMMAND} -DDQSKIN=$<TARGET_FILE:dqskin_cli>
    "-DARGS=${args}" "-DREGEX=${regex}" -DUNWRITTEN=${_optimize_dir}/bad.glb -DRIG=${_rig}
    -DSTILL=${_optimize_dir}/still_${name}.gltf
    -P ${CMAKE_CURRENT_SOURCE_DIR}/tests/optimize_refusal.cmake)
endforeach()
