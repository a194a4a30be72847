# Animation channels on the command line: duplicate channels (two channels of one animation for the same
# node and path) and KHR_animation_pointer. The inputs are written at configure time by
# scripts/testdata/make_animation_cases.py from testdata/twisted_cylinder.gltf (its docstring lists them), the
# pointer-animated copies at test time (animation_case.cmake says what each mode checks).
find_package(Python3 COMPONENTS Interpreter REQUIRED)
include(${CMAKE_CURRENT_LIST_DIR}/cli_test.cmake)
set(animation_generator ${PROJECT_SOURCE_DIR}/scripts/testdata/make_animation_cases.py)
set(animation_cases ${CMAKE_CURRENT_BINARY_DIR}/animation_cases)
execute_process(COMMAND ${Python3_EXECUTABLE} ${animation_generator} cases ${animation_cases} ${PROJECT_SOURCE_DIR}/testdata
  RESULT_VARIABLE _status OUTPUT_VARIABLE _output ERROR_VARIABLE _output)
if(NOT _status STREQUAL "0")
  message(FATAL_ERROR "scripts/testdata/make_animation_cases.py failed (${_status}):\n${_output}")
endif()
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${animation_generator}
  ${PROJECT_SOURCE_DIR}/scripts/testdata/gltf_builder.py ${PROJECT_SOURCE_DIR}/testdata/twisted_cylinder.gltf)
set(animation_scratch ${CMAKE_CURRENT_BINARY_DIR}/animation_scratch)
find_program(DQSKIN_NODE node)
set(animation_driver ${CMAKE_CURRENT_LIST_DIR}/animation_case.cmake)

# 14 repeats of a channel, byte for byte the same keys under accessors of their own: one warning, the
# same bake.
add_test(NAME cli.animation_identical_duplicates COMMAND ${CMAKE_COMMAND} -DDQSKIN=$<TARGET_FILE:dqskin_cli>
  -DMODE=identical -DFILE=${animation_cases}/dup_identical.gltf -DORIGINAL=${PROJECT_SOURCE_DIR}/testdata/twisted_cylinder.gltf
  -DWORK=${animation_scratch}/identical -P ${animation_driver})
# Two different channels for one node and path: bake refuses naming both, lint finds it, --fix keeps the
# first.
add_test(NAME cli.animation_different_duplicates COMMAND ${CMAKE_COMMAND} -DDQSKIN=$<TARGET_FILE:dqskin_cli>
  -DMODE=different -DFILE=${animation_cases}/dup_different.gltf
  -DORIGINAL=${PROJECT_SOURCE_DIR}/testdata/twisted_cylinder.gltf -DSECOND=${animation_cases}/dup_second_kept.gltf
  -DNODE=${DQSKIN_NODE} -DVALIDATOR=${CMAKE_BINARY_DIR}/tools/node_modules/gltf-validator
  -DVALIDATE_SCRIPT=${PROJECT_SOURCE_DIR}/scripts/check/validate_gltf.mjs
  -DWORK=${animation_scratch}/different -P ${animation_driver})
set_tests_properties(cli.animation_identical_duplicates cli.animation_different_duplicates PROPERTIES
  LABELS animation TIMEOUT 600)

# Pointers to a material's base color and a camera's field of view (in clip 'twist' and alone in 'zoom'):
# the file loads, with one warning per animation listing what is ignored.
dqskin_cli_test(cli.animation_pointer_ignored 0 ARGS info ${animation_cases}/pointer_ignored.gltf
  STDOUT "animation 0 'twist': 2 KHR_animation_pointer channels animating what dqskin does not deform are ignored: '/materials/0/pbrMetallicRoughness/baseColorFactor', '/cameras/0/perspective/yfov'\n *animation 1 'zoom': 1 KHR_animation_pointer channel animating what dqskin does not deform is ignored: '/cameras/0/perspective/yfov'\n"
  LABELS animation)

# Every channel as a KHR_animation_pointer channel deforms exactly as the original: the project's animated
# rigs (morph_skin's weights also as the mesh's weights) and the shared models (skipped when absent).
set(pointer_models "")
foreach(rig bending_arm camera_dolly eight_influences interpolation_modes morph_skin nonuniform_scale
            textured_cylinder twisted_cylinder two_skins uniform_scale)
  list(APPEND pointer_models "${rig}=${PROJECT_SOURCE_DIR}/testdata/${rig}.gltf")
endforeach()
set(shared ${PROJECT_SOURCE_DIR}/../shared/testdata)
foreach(model BrainStem/BrainStem.glb CesiumMan/CesiumMan.glb Fox/Fox.glb RiggedSimple/RiggedSimple.glb
              RiggedFigure/RiggedFigure.glb RecursiveSkeletons/RecursiveSkeletons.glb SimpleSkin/SimpleSkin.gltf
              raylib_robot/robot.glb raylib_greenman/greenman.glb)
  get_filename_component(stem ${model} NAME_WE)
  list(APPEND pointer_models "${stem}=${shared}/${model}")
endforeach()
foreach(entry IN LISTS pointer_models)
  string(REGEX REPLACE "=.*" "" name "${entry}")
  string(REGEX REPLACE "^[^=]*=" "" file "${entry}")
  add_test(NAME cli.animation_pointer_${name} COMMAND ${CMAKE_COMMAND} -DDQSKIN=$<TARGET_FILE:dqskin_cli>
    -DMODE=pointer -DPYTHON=${Python3_EXECUTABLE} -DSCRIPT=${animation_generator} -DA=${file}
    -DWORK=${animation_scratch}/pointer_${name} -P ${animation_driver})
  set_tests_properties(cli.animation_pointer_${name} PROPERTIES LABELS animation TIMEOUT 900
    SKIP_REGULAR_EXPRESSION "animation: SKIPPED")
endforeach()
add_test(NAME cli.animation_pointer_mesh_weights_morph_skin COMMAND ${CMAKE_COMMAND} -DDQSKIN=$<TARGET_FILE:dqskin_cli>
  -DMODE=pointer -DPYTHON=${Python3_EXECUTABLE} -DSCRIPT=${animation_generator}
  -DA=${PROJECT_SOURCE_DIR}/testdata/morph_skin.gltf -DMESH_WEIGHTS=ON
  -DWORK=${animation_scratch}/pointer_mesh_weights -P ${animation_driver})
set_tests_properties(cli.animation_pointer_mesh_weights_morph_skin PROPERTIES LABELS animation TIMEOUT 600)
