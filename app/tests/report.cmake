# `dqskin report` on the command line: help, the rigs' figures in report.json, bad input (one line, exit
# status, nothing written) and determinism. It draws contact sheets, so it needs a GL context (label gpu).
set(report_scratch ${CMAKE_CURRENT_BINARY_DIR}/report_cli)
set(report_rigs ${PROJECT_SOURCE_DIR}/testdata/twisted_cylinder.gltf ${PROJECT_SOURCE_DIR}/testdata/bending_arm.gltf
    ${PROJECT_SOURCE_DIR}/testdata/eight_influences.gltf)

include(${CMAKE_CURRENT_LIST_DIR}/cli_test.cmake)
function(dqskin_report_test name expected)
  dqskin_cli_test(cli.report_${name} ${expected} ${ARGN} ENVIRONMENT ${bake_test_environment} LABELS gpu)
  set_property(TEST cli.report_${name} APPEND PROPERTY FIXTURES_REQUIRED report_scratch)
endfunction()
add_test(NAME cli.report_clean_scratch COMMAND sh -c "rm -rf '${report_scratch}' && mkdir -p '${report_scratch}'")
set_tests_properties(cli.report_clean_scratch PROPERTIES FIXTURES_SETUP report_scratch)

dqskin_report_test(help 0 ARGS report --help
  STDOUT "INPUT.*--out.*--anim.*--fps.*--frames.*--resource-root.*--max-memory.*--tolerance.*--twist.*--candy-wrapper.*--bulge.*--worst-frames.*--image-size.*--fast-cpu.*Exit status")

# The rigs: one verdict line each, then the summary; report.json with the figures the rigs are built for.
dqskin_report_test(rigs 0 ARGS report ${report_rigs} -o ${report_scratch}/rigs --image-size 64
  STDERR "^add twist joints: child[^\n]*\nuse dqs: [^\n]*\nuse dqs: [^\n]*\nreported 93 frames \\(lbs, dqs and dib each\\) of 3 inputs in [0-9.]+ s into [^\n]*/rigs\n$")
foreach(rig twisted_cylinder bending_arm eight_influences)
  add_test(NAME cli.report_json_${rig} COMMAND ${CMAKE_COMMAND} -DFILE=${report_scratch}/rigs/${rig}/report.json -DRIG=${rig}
           -P ${PROJECT_SOURCE_DIR}/app/tests/report_json_check.cmake)
  set_tests_properties(cli.report_json_${rig} PROPERTIES DEPENDS cli.report_rigs FIXTURES_REQUIRED report_scratch)
endforeach()

# The pages of those reports in headless Chromium (lib/report/report_check.mjs): no console error, every
# joint of report.json in the table with its figures, the contact sheets shown. Skipped with a printed reason
# without Node.js or Chromium.
foreach(rig twisted_cylinder bending_arm eight_influences)
  add_test(NAME cli.report_page_${rig}
           COMMAND ${CMAKE_COMMAND} -DNODE=${DQSKIN_NODE} -DCHROMIUM=${DQSKIN_CHROMIUM}
                   -DSCRIPT=${PROJECT_SOURCE_DIR}/lib/report/report_check.mjs -DPAGE=${report_scratch}/rigs/${rig}
                   -DEXPECT=pass -P ${PROJECT_SOURCE_DIR}/lib/report/report_check.cmake)
  set_tests_properties(cli.report_page_${rig} PROPERTIES DEPENDS cli.report_rigs FIXTURES_REQUIRED report_scratch
                       LABELS report SKIP_REGULAR_EXPRESSION "report_check: SKIPPED" TIMEOUT 120)
endforeach()

# The frame flags of bake and render: 5 frames of the twist, 3 of them on the contact sheet.
dqskin_report_test(frame_selection 0 ARGS report ${PROJECT_SOURCE_DIR}/testdata/twisted_cylinder.gltf -o ${report_scratch}/frames
  --frames 0:8:2 --image-size 32 STDERR "\nreported 5 frames \\(lbs, dqs and dib each\\) of 1 input in")

# --fast-cpu says so in the settings.
dqskin_report_test(fast_cpu_is_recorded 0 ARGS report ${PROJECT_SOURCE_DIR}/testdata/bending_arm.gltf -o ${report_scratch}/fast
  --fast-cpu --quiet --image-size 32)
add_test(NAME cli.report_fast_cpu_in_settings COMMAND sh -c
  "grep -q '\"lbs\": \"fast-cpu\"' '${report_scratch}/fast/bending_arm/report.json' && grep -q '\"dib\": \"cpu-reference\"' '${report_scratch}/fast/bending_arm/report.json'")
set_tests_properties(cli.report_fast_cpu_in_settings PROPERTIES DEPENDS cli.report_fast_cpu_is_recorded FIXTURES_REQUIRED report_scratch)

# Bad input: one line naming the file, exit status 2, and no folder left behind.
dqskin_report_test(missing_input_exits_2 2 ARGS report ${report_scratch}/missing.gltf -o ${report_scratch}/missing
  STDERR "^dqskin: [^\n]*/missing.gltf: [^\n]+\n$")
add_test(NAME cli.report_missing_input_leaves_nothing COMMAND sh -c "test ! -e '${report_scratch}/missing'")
set_tests_properties(cli.report_missing_input_leaves_nothing PROPERTIES DEPENDS cli.report_missing_input_exits_2
  FIXTURES_REQUIRED report_scratch)
# A glTF file without a skin has nothing to report: a warning says so and the batch goes on, as bake bakes
# such a file; exit status 0, no folder for it, the others reported.
dqskin_report_test(unskinned_input_noted_exits_0 0 ARGS report ${PROJECT_SOURCE_DIR}/app/tests/report_unskinned.gltf
  ${PROJECT_SOURCE_DIR}/testdata/bending_arm.gltf -o ${report_scratch}/unskinned --image-size 32
  STDERR "^dqskin: [^\n]*report_unskinned.gltf: warning: no skinned mesh in the scene: nothing to report[^\n]*\n.*reported [0-9]+ frames [^\n]* of 1 input in")
add_test(NAME cli.report_unskinned_input_leaves_nothing COMMAND sh -c
  "test ! -e '${report_scratch}/unskinned/report_unskinned' && test -s '${report_scratch}/unskinned/bending_arm/report.json'")
set_tests_properties(cli.report_unskinned_input_leaves_nothing PROPERTIES DEPENDS cli.report_unskinned_input_noted_exits_0
  FIXTURES_REQUIRED report_scratch)
dqskin_report_test(bad_tolerance_exits_2 2 ARGS report ${PROJECT_SOURCE_DIR}/testdata/bending_arm.gltf -o ${report_scratch}/x
  --tolerance 5x STDERR "^dqskin: --tolerance '5x' is not a length or percentage \\(0.002, 0.5%\\)\n$")
dqskin_report_test(out_dir_required 2 ARGS report ${PROJECT_SOURCE_DIR}/testdata/bending_arm.gltf
  STDERR "^dqskin: -o OUTDIR is required\n$")

# Determinism: two runs, the same bytes (report.json, the contact sheet and the page).
add_test(NAME cli.report_is_deterministic COMMAND sh -c
  "for d in a b; do $<TARGET_FILE:dqskin_cli> report ${PROJECT_SOURCE_DIR}/testdata/twisted_cylinder.gltf -o '${report_scratch}/same_'$d --image-size 96 --quiet || exit 1; done && cmp '${report_scratch}/same_a/twisted_cylinder/report.json' '${report_scratch}/same_b/twisted_cylinder/report.json' && cmp '${report_scratch}/same_a/twisted_cylinder/worst_twist.png' '${report_scratch}/same_b/twisted_cylinder/worst_twist.png' && cmp '${report_scratch}/same_a/twisted_cylinder/report.html' '${report_scratch}/same_b/twisted_cylinder/report.html'")
set_tests_properties(cli.report_is_deterministic PROPERTIES FIXTURES_REQUIRED report_scratch ENVIRONMENT "${bake_test_environment}" LABELS gpu)
