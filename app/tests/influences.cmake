# More than 8 influences per vertex (scripts/testdata/make_influence_cases.py, generated at configure time by
# lib/CMakeLists.txt into DQSKIN_INFLUENCE_CASES_DIR): every command reads the 12- and 20-influence rigs,
# the summaries name the deformer that ran (every one takes up to 32 influences: none falls back), lint
# warns about runtimes that read fewer, and --max-influences cuts them as lint --fix does.
set(_cases ${DQSKIN_INFLUENCE_CASES_DIR})
set(_twenty ${_cases}/twenty_influences.gltf)
set(_work ${CMAKE_CURRENT_BINARY_DIR}/influences)

dqskin_cli_test(cli.influences_info_twenty 0 ARGS info ${_twenty}
  STDOUT "up to 20 influences per vertex \\(JOINTS_0..JOINTS_4\\)" LABELS influences)
dqskin_cli_test(cli.influences_info_twelve 0 ARGS info ${_cases}/twelve_influences.gltf
  STDOUT "up to 12 influences per vertex \\(JOINTS_0..JOINTS_2\\)" LABELS influences)
# three.js reads JOINTS_0 only, Babylon.js JOINTS_0 and JOINTS_1: a warning, not an error.
dqskin_cli_test(cli.influences_lint_warns 1 ARGS lint ${_twenty}
  STDOUT "warning over-8-influences \\(164\\): 20 joints with weight \\(Babylon.js reads 8, three.js 4" LABELS influences)
dqskin_cli_test(cli.influences_lint_allowed 0 ARGS lint --max-influences 20 ${_twenty} STDOUT ": clean\n"
  LABELS influences)
dqskin_cli_test(cli.influences_lint_fix_past_cap 2 ARGS lint --fix --max-influences 33 ${_twenty} -o ${_work}/never.glb
  STDERR "--max-influences must be from 1 to 32 for --fix" LABELS influences)

foreach(_backend cpu fast-cpu)
  set(_named ${_backend})
  if(_backend STREQUAL "cpu")
    set(_named cpu-reference)
  endif()
  foreach(_file twelve twenty)
    dqskin_cli_test(cli.influences_bake_${_file}_${_backend} 0
      ARGS bake ${_cases}/${_file}_influences.gltf -o ${_work}/bake_${_file}_${_backend} --format ply,glb --fps 8
           --backend ${_backend} --force -v
      STDERR "frames deformed on ${_named}.*\ndeformer: ${_named}" LABELS influences)
  endforeach()
endforeach()
dqskin_cli_test(cli.influences_render_twenty 0
  ARGS render ${_twenty} -o ${_work}/render --size 96x96 --fps 4 --backend fast-cpu --force
  STDERR "deformed on fast-cpu" ENVIRONMENT ${bake_test_environment} LABELS influences gpu)
dqskin_cli_test(cli.influences_report_twenty 0 ARGS report ${_twenty} -o ${_work}/report --fps 4
  ENVIRONMENT ${bake_test_environment} LABELS influences gpu)
dqskin_cli_test(cli.influences_flag_past_cap 2 ARGS bake ${_twenty} -o ${_work}/never --max-influences 33
  STDERR "--max-influences must be from 1 to 32" LABELS influences)

# 4: what three.js reads; 12: three sets, past what any runtime reads, so that lint --fix writes JOINTS_2.
foreach(_keep 4 12)
  add_test(NAME cli.influences_max_influences_${_keep} COMMAND ${CMAKE_COMMAND} -DDQSKIN=$<TARGET_FILE:dqskin_cli>
    -DFILE=${_twenty} -DCUT=${_cases}/twenty_influences_top${_keep}.gltf -DKEEP=${_keep} -DBACKEND=cpu
    -DWORK=${_work}/cut${_keep} -P ${CMAKE_CURRENT_LIST_DIR}/influence_cut.cmake)
  set_tests_properties(cli.influences_max_influences_${_keep} PROPERTIES LABELS influences TIMEOUT 300)
endforeach()
