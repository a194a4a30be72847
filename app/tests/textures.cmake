# Textures stored the ways real exports store them (scripts/make_texture_cases.py, generated here at
# configure time): EXT_texture_webp with and without a core fallback, KHR_texture_basisu with and without
# one. `render` must draw the WebP image, or the fallback, or the material's factors with one warning.
find_package(Python3 COMPONENTS Interpreter REQUIRED)
set(texture_cases ${CMAKE_CURRENT_BINARY_DIR}/texture_cases)
set(_texture_generator ${PROJECT_SOURCE_DIR}/scripts/make_texture_cases.py)
execute_process(COMMAND ${Python3_EXECUTABLE} ${_texture_generator} ${texture_cases}
  RESULT_VARIABLE _status OUTPUT_VARIABLE _output ERROR_VARIABLE _output)
if(NOT _status STREQUAL "0")
  message(FATAL_ERROR "scripts/make_texture_cases.py failed (${_status}):\n${_output}")
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
         -DSCRIPT=${PROJECT_SOURCE_DIR}/scripts/validate_gltf.mjs)
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

