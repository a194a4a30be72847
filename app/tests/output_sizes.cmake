# Outputs at their true size: primitives that share vertex data write each distinct vertex once (ply, obj,
# vat in every profile, morph), and every VAT and bone texture plans its sides within --max-size (default
# 8192), wrapping where its runtime reads wrapped rows and refusing in one line, with the size that would
# fit, where it cannot. Inputs from scripts/testdata/make_shared_vertex_cases.py, generated at configure time.
find_package(Python3 COMPONENTS Interpreter REQUIRED)
set(size_cases ${CMAKE_CURRENT_BINARY_DIR}/size_cases)
set(size_scratch ${CMAKE_CURRENT_BINARY_DIR}/size_outputs)
set(_size_generator ${PROJECT_SOURCE_DIR}/scripts/testdata/make_shared_vertex_cases.py)
execute_process(COMMAND ${Python3_EXECUTABLE} ${_size_generator} ${size_cases}
  RESULT_VARIABLE _status OUTPUT_VARIABLE _output ERROR_VARIABLE _output)
if(NOT _status STREQUAL "0")
  message(FATAL_ERROR "scripts/testdata/make_shared_vertex_cases.py failed (${_status}):\n${_output}")
endif()
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${_size_generator}
  ${PROJECT_SOURCE_DIR}/scripts/testdata/make_rigs.py ${PROJECT_SOURCE_DIR}/scripts/testdata/gltf_builder.py)

# The checks of app/tests/output_sizes.py, which documents them.
foreach(kind shared wide)
  add_test(NAME sizes.${kind}_outputs COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/app/tests/output_sizes.py
    ${kind} $<TARGET_FILE:dqskin_cli> ${size_cases} ${size_scratch}/${kind})
  set_tests_properties(sizes.${kind}_outputs PROPERTIES FIXTURES_SETUP size_outputs_${kind} LABELS sizes TIMEOUT 300
    ENVIRONMENT "${bake_test_environment}")
endforeach()
# The glTF outputs of the shared case (rest.glb, OpenVAT's NAME.glb, Houdini's NAME_mesh.glb, animation.glb)
# through the Khronos glTF-Validator (scripts/install/node_tools.sh; skipped with the reason when missing).
find_program(DQSKIN_NODE node)
add_test(NAME sizes.shared_outputs_validator COMMAND sh -c
  "if [ ! -f '${CMAKE_BINARY_DIR}/tools/node_modules/gltf-validator/package.json' ] || [ -z '${DQSKIN_NODE}' ]; then echo 'SKIP: the glTF-Validator is not installed (scripts/install/node_tools.sh)'; exit 0; fi; exec '${DQSKIN_NODE}' '${PROJECT_SOURCE_DIR}/scripts/check/validate_gltf.mjs' --validator '${CMAKE_BINARY_DIR}/tools/node_modules/gltf-validator' '${size_scratch}/shared'")
set_tests_properties(sizes.shared_outputs_validator PROPERTIES FIXTURES_REQUIRED size_outputs_shared LABELS sizes
  SKIP_REGULAR_EXPRESSION "SKIP: ")

# A layout that cannot fit: one line naming the clip, the size it needs and the smallest --max-size that
# would fit it; nothing written.
include(${CMAKE_CURRENT_LIST_DIR}/outcome_test.cmake)
function(dqskin_size_refusal name)
  dqskin_outcome_case(sizes.${name} 2 WORKING_DIRECTORY ${size_cases} LABEL sizes CTEST_TIMEOUT 120
    FOLDER ${size_scratch}/${name} UNCHANGED ONE_LINE ${ARGN})
endfunction()
# Houdini reads one image: 9,001 frames of one 9,000-texel row do not fit 8192 rows.
dqskin_size_refusal(houdini_too_many_frames ARGS bake wide_tube.gltf -o ${size_scratch}/houdini_too_many_frames
  --format vat --vat-profile houdini
  STDERR "^dqskin: wide_tube.gltf: clip sway: 9000 vertices × 9001 frames do not fit an image 8192 texels high \\(at most 4096 frames do\\)[^\n]*; it needs 9000 × 9001 texels: --max-size 9001 would fit\n$")
# OpenVAT's packed normals double the rows: no wrap within 8192 holds 2 × 9,001 rows.
dqskin_size_refusal(openvat_too_many_frames ARGS bake wide_tube.gltf -o ${size_scratch}/openvat_too_many_frames
  --format vat --vat-profile openvat
  STDERR "^dqskin: wide_tube.gltf: clip sway: 9000 vertices × 9001 frames do not fit OpenVAT's layout within 8192 texels a side; it needs 9000 × 18002 texels: --max-size 18002 would fit\n$")
# Bone textures: Babylon.js reads one row per frame.
dqskin_size_refusal(mat4_bones_too_many_frames ARGS bake wide_tube.gltf -o ${size_scratch}/mat4_bones_too_many_frames
  --format bones --bones-profile mat4
  STDERR "^dqskin: wide_tube.gltf: clip sway: skin 0: the mat4 bone texture needs 12 × 9001 texels, over --max-size 8192 \\(its runtime reads one row per frame and does not wrap\\); --max-size 9001 would fit, as would fewer frames \\(--fps\\)\n$")
# Cocos reads one square texture.
dqskin_size_refusal(cocos_bones_over_max_size ARGS bake wide_tube.gltf -o ${size_scratch}/cocos_bones_over_max_size
  --format bones --bones-profile dq-cocos --max-size 200
  STDERR "^dqskin: wide_tube.gltf: clip sway: skin 0: the dq-cocos bone texture needs 240 × 240 texels, over --max-size 200 \\(Cocos reads one square texture\\); --max-size 240 would fit\n$")
