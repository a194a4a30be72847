# Outputs at their true size: primitives that share vertex data write each distinct vertex once (ply, obj,
# vat in every profile, morph). Inputs from scripts/make_shared_vertex_cases.py, generated at configure time.
find_package(Python3 COMPONENTS Interpreter REQUIRED)
set(size_cases ${CMAKE_CURRENT_BINARY_DIR}/size_cases)
set(size_scratch ${CMAKE_CURRENT_BINARY_DIR}/size_outputs)
set(_size_generator ${PROJECT_SOURCE_DIR}/scripts/make_shared_vertex_cases.py)
execute_process(COMMAND ${Python3_EXECUTABLE} ${_size_generator} ${size_cases}
  RESULT_VARIABLE _status OUTPUT_VARIABLE _output ERROR_VARIABLE _output)
if(NOT _status STREQUAL "0")
  message(FATAL_ERROR "scripts/make_shared_vertex_cases.py failed (${_status}):\n${_output}")
endif()
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${_size_generator}
  ${PROJECT_SOURCE_DIR}/scripts/make_rigs.py ${PROJECT_SOURCE_DIR}/scripts/gltf_builder.py)

# The checks of app/tests/output_sizes.py, which documents them.
foreach(kind shared)
  add_test(NAME sizes.${kind}_outputs COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/app/tests/output_sizes.py
    ${kind} $<TARGET_FILE:dqskin_cli> ${size_cases} ${size_scratch}/${kind})
  set_tests_properties(sizes.${kind}_outputs PROPERTIES FIXTURES_SETUP size_outputs_${kind} LABELS sizes TIMEOUT 300
    ENVIRONMENT "${bake_test_environment}")
endforeach()
# The glTF outputs of the shared case (rest.glb, OpenVAT's NAME.glb, Houdini's NAME_mesh.glb, animation.glb)
# through the Khronos glTF-Validator (scripts/install-node-tools.sh; skipped with the reason when missing).
find_program(DQSKIN_NODE node)
add_test(NAME sizes.shared_outputs_validator COMMAND sh -c
  "if [ ! -f '${CMAKE_BINARY_DIR}/tools/node_modules/gltf-validator/package.json' ] || [ -z '${DQSKIN_NODE}' ]; then echo 'SKIP: the glTF-Validator is not installed (scripts/install-node-tools.sh)'; exit 0; fi; exec '${DQSKIN_NODE}' '${PROJECT_SOURCE_DIR}/scripts/validate_gltf.mjs' --validator '${CMAKE_BINARY_DIR}/tools/node_modules/gltf-validator' '${size_scratch}/shared'")
set_tests_properties(sizes.shared_outputs_validator PROPERTIES FIXTURES_REQUIRED size_outputs_shared LABELS sizes
  SKIP_REGULAR_EXPRESSION "SKIP: ")
