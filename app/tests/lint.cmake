# `dqskin lint` on the command line: every file of the bad-skin catalogue (testdata/bad_skins/, written by
# scripts/testdata/make_bad_skins.py) gives its exit status and its one check id in --json; --fix removes what it can
# fix, keeps the rest, and writes a file the Khronos glTF-Validator accepts; the project's rigs lint as
# known; the JUnit report is well-formed; usage errors; and every shared model lints without a crash.
include(${CMAKE_CURRENT_LIST_DIR}/cli_test.cmake)
set(lint_scratch ${CMAKE_CURRENT_BINARY_DIR}/lint_cli)
file(REMOVE_RECURSE ${lint_scratch})
set(bad_skins ${PROJECT_SOURCE_DIR}/testdata/bad_skins)

# name: FILE stem; status: lint's exit status; check: the id it must find ("" for none); fixable: ON when
# --fix removes it; fixed_status: the fixed file's exit status; validate: OFF where the fixed file keeps a
# problem the validator itself refuses (joints without a common root).
function(dqskin_lint_case name status check fixable fixed_status validate)
  add_test(NAME cli.lint_${name} COMMAND ${CMAKE_COMMAND} -DDQSKIN=$<TARGET_FILE:dqskin_cli>
    -DFILE=${bad_skins}/${name}.gltf -DEXPECTED=${status} -DCHECKS=${check} -DWORK=${lint_scratch}/${name}
    -DFIX=ON -DFIXABLE=${fixable} -DFIXED_EXPECTED=${fixed_status} -DVALIDATE=${validate} -DNODE=${DQSKIN_NODE}
    -DVALIDATOR=${CMAKE_BINARY_DIR}/tools/node_modules/gltf-validator
    -DSCRIPT=${PROJECT_SOURCE_DIR}/scripts/check/validate_gltf.mjs -P ${CMAKE_CURRENT_LIST_DIR}/lint_case.cmake)
  set_tests_properties(cli.lint_${name} PROPERTIES LABELS lint)
endfunction()
dqskin_lint_case(clean 0 "" ON 0 ON)
dqskin_lint_case(weights_sum_float 2 weight-sum ON 0 ON)
dqskin_lint_case(weights_sum_ubyte 2 weight-sum ON 0 ON)
dqskin_lint_case(weights_sum_ushort 2 weight-sum ON 0 ON)
dqskin_lint_case(five_influences 1 too-many-influences ON 0 ON)
dqskin_lint_case(nine_influences 1 over-8-influences ON 0 ON)
dqskin_lint_case(zero_weight_vertex 2 zero-weight-vertex ON 0 ON)
dqskin_lint_case(negative_weight 2 negative-weight ON 0 ON)
dqskin_lint_case(duplicate_joint 2 duplicate-joint ON 0 ON)
dqskin_lint_case(joint_out_of_range 2 joint-out-of-range ON 0 ON)
dqskin_lint_case(skeleton_not_root 2 skeleton-not-root ON 0 ON)
dqskin_lint_case(non_unit_rotation_keys 2 rotation-not-unit ON 0 ON)
dqskin_lint_case(hemisphere_flip_keys 1 hemisphere-flip ON 0 ON)
dqskin_lint_case(hemisphere_flip_cubic 1 hemisphere-flip ON 0 ON)
dqskin_lint_case(unused_joint 0 unused-joint OFF 0 ON)
dqskin_lint_case(no_common_root 2 no-common-root OFF 2 OFF)
dqskin_lint_case(wrong_inverse_bind 1 inverse-bind-mismatch OFF 1 ON)
dqskin_lint_case(nonuniform_scaled_joint 1 joint-nonuniform-scale OFF 1 ON)
dqskin_lint_case(uniform_scaled_joint 0 joint-uniform-scale OFF 0 ON)
# Legal (a joint scaled at rest, its inverse bind matrix scaling back): clean.
dqskin_lint_case(non_orthonormal_ibm 0 "" OFF 0 ON)

# Generated cases (scripts/testdata/make_hostile_commands.py lint_cases, in DQSKIN_HOSTILE_DIR/lint), the same way.
# A mesh drawn by a two-joint and a three-joint skin, one vertex on joint 2: a warning, and --fix keeps
# the influence (it dropped it, checking against the smaller skin).
function(dqskin_lint_generated_case name status check fixable fixed_status validate)
  add_test(NAME cli.lint_${name} COMMAND ${CMAKE_COMMAND} -DDQSKIN=$<TARGET_FILE:dqskin_cli>
    -DFILE=${DQSKIN_HOSTILE_DIR}/lint/${name}.gltf -DEXPECTED=${status} -DCHECKS=${check} -DWORK=${lint_scratch}/${name}
    -DFIX=ON -DFIXABLE=${fixable} -DFIXED_EXPECTED=${fixed_status} -DVALIDATE=${validate} -DNODE=${DQSKIN_NODE}
    -DVALIDATOR=${CMAKE_BINARY_DIR}/tools/node_modules/gltf-validator
    -DSCRIPT=${PROJECT_SOURCE_DIR}/scripts/check/validate_gltf.mjs -P ${CMAKE_CURRENT_LIST_DIR}/lint_case.cmake)
  set_tests_properties(cli.lint_${name} PROPERTIES LABELS lint)
endfunction()
dqskin_lint_generated_case(two_skins_one_mesh 1 joint-beyond-smaller-skin OFF 1 OFF)
# Rotation keys of length 0 (one in a channel, and a whole channel): --fix wrote them unchanged.
dqskin_lint_generated_case(zero_rotation_keys 2 rotation-not-unit ON 0 ON)

# SIGTERM while --fix writes its output, and while it reads: one line, the process ends by the signal, no
# temporary and no output (it left a truncated temporary and said nothing).
add_test(NAME cli.lint_fix_stopped_by_sigterm COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/lint_fix_signal.sh
  $<TARGET_FILE:dqskin_cli> ${DQSKIN_HOSTILE_DIR}/lint/unweighted_4m.gltf ${lint_scratch}/stopped)
set_tests_properties(cli.lint_fix_stopped_by_sigterm PROPERTIES LABELS lint TIMEOUT 300)

# The project's rigs: clean, but for the two that show a rule on purpose.
foreach(rig bending_arm camera_dolly interpolation_modes morph_skin textured_cylinder twisted_cylinder two_skins)
  dqskin_cli_test(cli.lint_rig_${rig} 0 ARGS lint ${PROJECT_SOURCE_DIR}/testdata/${rig}.gltf
    STDOUT "^[^\n]*${rig}.gltf: clean\nsummary: clean" LABELS lint)
endforeach()
dqskin_cli_test(cli.lint_rig_eight_influences 1 ARGS lint ${PROJECT_SOURCE_DIR}/testdata/eight_influences.gltf
  STDOUT "warning too-many-influences \\(52\\): 8 joints with weight" LABELS lint)
dqskin_cli_test(cli.lint_rig_eight_influences_allowed 0 ARGS lint --max-influences 8
  ${PROJECT_SOURCE_DIR}/testdata/eight_influences.gltf STDOUT ": clean\n" LABELS lint)
dqskin_cli_test(cli.lint_rig_nonuniform_scale 1 ARGS lint ${PROJECT_SOURCE_DIR}/testdata/nonuniform_scale.gltf
  STDOUT "warning joint-nonuniform-scale \\(1\\)" LABELS lint)
dqskin_cli_test(cli.lint_rig_uniform_scale 0 ARGS lint ${PROJECT_SOURCE_DIR}/testdata/uniform_scale.gltf
  STDOUT "info    joint-uniform-scale \\(1\\)" LABELS lint)

# Several files: the worst decides; an unreadable one is one line on stderr, exit 2, the others still linted.
dqskin_cli_test(cli.lint_unreadable_file_others_linted 2 ARGS lint ${bad_skins}/clean.gltf
  ${lint_scratch}/no_such.gltf ${bad_skins}/five_influences.gltf
  STDOUT "clean.gltf: clean\n[^\n]*no_such.gltf: error: [^\n]*\n[^\n]*five_influences.gltf: warning\n"
  STDERR "^dqskin: [^\n]*no_such.gltf: [^\n]*\n$" LABELS lint)
dqskin_cli_test(cli.lint_werror 2 ARGS lint --werror ${bad_skins}/five_influences.gltf LABELS lint)
dqskin_cli_test(cli.lint_fix_refuses_several_inputs 2 ARGS lint --fix ${bad_skins}/clean.gltf
  ${bad_skins}/five_influences.gltf -o ${lint_scratch}/x.glb STDERR "^dqskin: --fix takes one input" LABELS lint)
dqskin_cli_test(cli.lint_output_needs_fix 2 ARGS lint ${bad_skins}/clean.gltf -o ${lint_scratch}/x.glb
  STDERR "^dqskin: --fix and -o go together" LABELS lint)
dqskin_cli_test(cli.lint_help 0 ARGS lint --help
  STDOUT "--sum-tolerance.*--max-influences.*--bind-tolerance.*--werror.*--fix.*--json.*--junit.*weight-sum.*hemisphere-flip.*Exit status: 0 clean"
  LABELS lint)

# JUnit: a file that an XML parser reads (Python's, where there is one), with a testcase per file and check.
add_test(NAME cli.lint_junit COMMAND ${CMAKE_COMMAND} -DDQSKIN=$<TARGET_FILE:dqskin_cli> -DDIR=${bad_skins}
  -DOUT=${lint_scratch}/junit.xml -P ${CMAKE_CURRENT_LIST_DIR}/lint_junit.cmake)
set_tests_properties(cli.lint_junit PROPERTIES LABELS lint)

# Every shared model: lint runs, exits 0, 1 or 2, prints one report, never crashes; skipped when absent.
add_test(NAME cli.lint_shared_models COMMAND ${CMAKE_COMMAND} -DDQSKIN=$<TARGET_FILE:dqskin_cli>
  -DDIR=${PROJECT_SOURCE_DIR}/../shared/testdata -P ${CMAKE_CURRENT_LIST_DIR}/lint_models.cmake)
set_tests_properties(cli.lint_shared_models PROPERTIES LABELS lint SKIP_REGULAR_EXPRESSION "lint: SKIPPED" TIMEOUT 600)

# The fixed copy deforms like the original where the fix only changes how the data is stored.
foreach(input ${bad_skins}/duplicate_joint.gltf ${bad_skins}/hemisphere_flip_keys.gltf
              ${bad_skins}/non_unit_rotation_keys.gltf ${PROJECT_SOURCE_DIR}/../shared/testdata/raylib_robot/robot.glb)
  get_filename_component(stem ${input} NAME_WE)
  add_test(NAME cli.lint_fix_deforms_the_same_${stem} COMMAND ${CMAKE_COMMAND} -DDQSKIN=$<TARGET_FILE:dqskin_cli>
    -DFILE=${input} -DWORK=${lint_scratch}/same_${stem} -P ${CMAKE_CURRENT_LIST_DIR}/lint_same_deformation.cmake)
  set_tests_properties(cli.lint_fix_deforms_the_same_${stem} PROPERTIES LABELS lint
    SKIP_REGULAR_EXPRESSION "lint: SKIPPED" TIMEOUT 900)
endforeach()

# A compressed file (gltfpack -c) is linted, but --fix refuses to write it back; an output that cannot be
# written is one line and exit status 2.
add_test(NAME cli.lint_fix_refuses_compressed COMMAND ${CMAKE_COMMAND} -DDQSKIN=$<TARGET_FILE:dqskin_cli>
  -DTOOLS=${CMAKE_BINARY_DIR}/tools/node_modules/.bin -DFILE=${bad_skins}/clean.gltf -DWORK=${lint_scratch}/compressed
  -P ${CMAKE_CURRENT_LIST_DIR}/lint_compressed.cmake)
set_tests_properties(cli.lint_fix_refuses_compressed PROPERTIES LABELS lint SKIP_REGULAR_EXPRESSION "lint: SKIPPED")
dqskin_cli_test(cli.lint_fix_unwritable_output 2 ARGS lint --fix ${bad_skins}/clean.gltf
  -o /proc/dqskin-cannot-write-here/x.glb STDOUT "clean.gltf: clean\n"
  STDERR "^dqskin: /proc/dqskin-cannot-write-here/x.glb: [^\n]*\n$" LABELS lint)
