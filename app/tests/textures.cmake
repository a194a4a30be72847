# Textures stored the ways real exports store them (scripts/testdata/make_texture_cases.py, generated here at
# configure time): EXT_texture_webp with and without a core fallback, KHR_texture_basisu with and without
# one. `render` must draw the WebP image, or the fallback, or the material's factors with one warning.
find_package(Python3 COMPONENTS Interpreter REQUIRED)
set(texture_cases ${CMAKE_CURRENT_BINARY_DIR}/texture_cases)
set(_texture_generator ${PROJECT_SOURCE_DIR}/scripts/testdata/make_texture_cases.py)
execute_process(COMMAND ${Python3_EXECUTABLE} ${_texture_generator} ${texture_cases}
  RESULT_VARIABLE _status OUTPUT_VARIABLE _output ERROR_VARIABLE _output)
if(NOT _status STREQUAL "0")
  message(FATAL_ERROR "scripts/testdata/make_texture_cases.py failed (${_status}):\n${_output}")
endif()
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${_texture_generator}
  ${PROJECT_SOURCE_DIR}/testdata/textured_cylinder.gltf)

set(texture_scratch ${CMAKE_CURRENT_BINARY_DIR}/texture_render)
set(textured ${PROJECT_SOURCE_DIR}/testdata/textured_cylinder.gltf)
# texture_render_test(NAME CASE REFERENCE UNLIKE [WARNING regex])
function(texture_render_test name case reference unlike)
  set(args -DDQSKIN=$<TARGET_FILE:dqskin_cli> -DCASE=${texture_cases}/${case} -DREFERENCE=${reference}
           -DUNLIKE=${unlike} -DOUT=${texture_scratch}/${name})
  if(ARGC GREATER 4)
    list(APPEND args "-DWARNING=${ARGV4}")
  endif()
  add_test(NAME cli.texture_${name} COMMAND ${CMAKE_COMMAND} ${args}
    -P ${PROJECT_SOURCE_DIR}/app/tests/texture_render_case.cmake)
  set_tests_properties(cli.texture_${name} PROPERTIES ENVIRONMENT "${bake_test_environment}" LABELS gpu)
endfunction()

set(untextured ${texture_cases}/untextured.gltf)
# The WebP image alone, through the extension (required): drawn as the PNG original is.
texture_render_test(webp_drawn webp_only.gltf ${textured} ${untextured})
# The extension's WebP image, not the core source's magenta fallback.
texture_render_test(webp_preferred_to_fallback webp_fallback.gltf ${textured} ${untextured})
# KHR_texture_basisu with a PNG fallback: the fallback is drawn.
texture_render_test(basisu_fallback_drawn basisu_fallback.gltf ${textured} ${untextured})
# KHR_texture_basisu alone: the material's factors (as without a texture), and one warning saying so.
texture_render_test(basisu_only_factors basisu_only.gltf ${untextured} ${textured}
  "texture 0 has only a KTX2 image \\(KHR_texture_basisu\\), which dqskin does not decode, and no PNG or JPEG fallback. materials using it are drawn with their factors")

# ---- bake --format glb --glb-images: where the frames' images go -------------------------------------------
set(glb_images_scratch ${CMAKE_CURRENT_BINARY_DIR}/glb_images)
set(glb_validator ${CMAKE_BINARY_DIR}/tools/node_modules/gltf-validator)
find_program(DQSKIN_NODE node)
foreach(mode shared embed none)
  set(args -DDQSKIN=$<TARGET_FILE:dqskin_cli> -DINPUT=${textured} -DOUT=${glb_images_scratch}/${mode} -DMODE=${mode})
  if(DQSKIN_NODE)
    list(APPEND args -DNODE=${DQSKIN_NODE} -DVALIDATOR=${glb_validator}
         -DSCRIPT=${PROJECT_SOURCE_DIR}/scripts/check/validate_gltf.mjs)
  endif()
  add_test(NAME cli.glb_images_${mode} COMMAND ${CMAKE_COMMAND} ${args}
    -P ${PROJECT_SOURCE_DIR}/app/tests/glb_images_case.cmake)
  set_tests_properties(cli.glb_images_${mode} PROPERTIES ENVIRONMENT "${bake_test_environment}" LABELS gpu
    FIXTURES_SETUP glb_images_${mode} SKIP_REGULAR_EXPRESSION "SKIP: ")
endforeach()
# A frame that references its shared image is drawn as the embedded one, and not as one without images.
set(frame textured_cylinder/twist/frame_0002.glb)
add_test(NAME cli.glb_images_shared_frame_drawn_textured COMMAND ${CMAKE_COMMAND} -DDQSKIN=$<TARGET_FILE:dqskin_cli>
  -DCASE=${glb_images_scratch}/shared/${frame} -DREFERENCE=${glb_images_scratch}/embed/${frame}
  -DUNLIKE=${glb_images_scratch}/none/${frame} -DOUT=${texture_scratch}/shared_frame -DTIME=0
  -P ${PROJECT_SOURCE_DIR}/app/tests/texture_render_case.cmake)
set_tests_properties(cli.glb_images_shared_frame_drawn_textured PROPERTIES ENVIRONMENT "${bake_test_environment}"
  LABELS gpu FIXTURES_REQUIRED "glb_images_shared;glb_images_embed;glb_images_none")
dqskin_cli_test(cli.glb_images_unknown_mode 2 ARGS bake ${textured} -o ${glb_images_scratch}/bad --glb-images inline
  STDERR "^dqskin: --glb-images 'inline' is not one of embed, shared, none\n$")

# ---- the meshes beside textures keep the source's look ---------------------------------------------------
# Each is baked from the textured cylinder, then drawn (no animation: its rest pose) against the source at
# time 0 (the clip starts at the rest pose): the checker and the colour gradient must show, not the
# untextured rig's plain surface. Every .glb of the bake must be validator-clean.
set(look_scratch ${CMAKE_CURRENT_BINARY_DIR}/mesh_look)
foreach(case vat:dqskin:rest.glb vat:openvat:textured_cylinder.glb vat:houdini:textured_cylinder_mesh.glb
             bones:dq:bones_mesh.glb)
  string(REPLACE ":" ";" case "${case}")
  list(GET case 0 format)
  list(GET case 1 profile)
  list(GET case 2 file)
  set(name ${format}_${profile})
  dqskin_cli_test(cli.mesh_look_bake_${name} 0 ARGS bake ${textured} -o ${look_scratch}/${name} --format ${format}
    --${format}-profile ${profile} --fps 4 --force --quiet ENVIRONMENT ${bake_test_environment} LABELS gpu)
  set_tests_properties(cli.mesh_look_bake_${name} PROPERTIES FIXTURES_SETUP mesh_look_${name})
  add_test(NAME cli.mesh_look_drawn_${name} COMMAND ${CMAKE_COMMAND} -DDQSKIN=$<TARGET_FILE:dqskin_cli>
    -DCASE=${look_scratch}/${name}/textured_cylinder/twist/${file} -DREFERENCE=${textured} -DUNLIKE=${untextured}
    -DOUT=${texture_scratch}/look_${name} -DTIME=0 -P ${PROJECT_SOURCE_DIR}/app/tests/texture_render_case.cmake)
  set_tests_properties(cli.mesh_look_drawn_${name} PROPERTIES ENVIRONMENT "${bake_test_environment}" LABELS gpu
    FIXTURES_REQUIRED mesh_look_${name})
  if(DQSKIN_NODE)
    add_test(NAME cli.mesh_look_validator_${name} COMMAND ${DQSKIN_NODE} ${PROJECT_SOURCE_DIR}/scripts/check/validate_gltf.mjs
      --validator ${glb_validator} ${look_scratch}/${name})
    set_tests_properties(cli.mesh_look_validator_${name} PROPERTIES FIXTURES_REQUIRED mesh_look_${name})
  endif()
endforeach()
