# bake --format glb --glb-images MODE on a textured rig: where the frames' images go.
#   cmake -DDQSKIN=dqskin -DINPUT=rig.gltf -DOUT=dir -DMODE=embed|shared|none [-DNODE=node -DVALIDATOR=dir
#         -DSCRIPT=validate_gltf.mjs] -P glb_images_case.cmake
# Checks, for the one animation folder OUT/<input>/<clip>:
#   shared: each source image once, as image_<i>.<ext> beside the frames, listed in the manifest with its
#           hash; every frame references it by URI and holds no image bytes; `dqskin verify` passes, and
#           fails once the image is changed (it is one of the bake's outputs); two shards merge into the
#           unsharded bake's manifest, and shards baked with other modes are refused by `dqskin merge`;
#   embed:  no image file; every frame holds the image's bytes;
#   none:   no image file; no frame has images, textures or samplers.
# With NODE, VALIDATOR and SCRIPT, the Khronos glTF-Validator must find no error in any frame (the shared
# images are validated with each frame that references them).
file(REMOVE_RECURSE ${OUT} ${OUT}_shards)
set(modes shared embed)  # of the two shards whose merge is refused
execute_process(COMMAND ${DQSKIN} bake ${INPUT} -o ${OUT} --format glb --fps 4 --glb-images ${MODE} --quiet
                RESULT_VARIABLE status ERROR_VARIABLE err TIMEOUT 300)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "dqskin bake --glb-images ${MODE}: exit status ${status}\n${err}")
endif()
file(GLOB_RECURSE frames ${OUT}/*.glb)
list(LENGTH frames frame_count)
if(frame_count LESS 2)
  message(FATAL_ERROR "expected the clip's frames in ${OUT}, found ${frame_count}")
endif()
file(GLOB_RECURSE images ${OUT}/image_*)
file(READ ${OUT}/manifest.json manifest)

foreach(frame IN LISTS frames)
  file(READ ${frame} text OFFSET 20)  # the JSON chunk, after the 12-byte header and its own 8; NUL ends it
  string(REGEX MATCH "\"images\":\\[[^]]*\\]" frame_images "${text}")
  if(MODE STREQUAL "shared")
    if(NOT frame_images MATCHES "\"uri\":\"image_0\\.png\"" OR frame_images MATCHES "bufferView")
      message(FATAL_ERROR "${frame}: images should be one URI to image_0.png, not '${frame_images}'")
    endif()
  elseif(MODE STREQUAL "embed")
    if(NOT frame_images MATCHES "\"bufferView\"")
      message(FATAL_ERROR "${frame}: the image should be embedded, not '${frame_images}'")
    endif()
  elseif(frame_images OR text MATCHES "\"textures\"|\"samplers\"|baseColorTexture")
    message(FATAL_ERROR "${frame}: has images, textures or samplers with --glb-images none")
  endif()
endforeach()

if(MODE STREQUAL "shared")
  list(LENGTH images image_count)
  if(NOT image_count EQUAL 1)
    message(FATAL_ERROR "expected one image file beside the frames, found ${image_count}: ${images}")
  endif()
  file(SHA256 ${images} digest)
  if(NOT manifest MATCHES "\"path\": \"[^\"]*/image_0\\.png\",[ \n]*\"sha256\": \"${digest}\"")
    message(FATAL_ERROR "the manifest does not list image_0.png with its hash ${digest}")
  endif()
  execute_process(COMMAND ${DQSKIN} verify ${OUT} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "dqskin verify ${OUT}: exit status ${status}\n${out}${err}")
  endif()
  file(APPEND ${images} "x")
  execute_process(COMMAND ${DQSKIN} verify ${OUT} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
  if(status EQUAL 0 OR NOT "${out}${err}" MATCHES "image_0\\.png")
    message(FATAL_ERROR "dqskin verify should fail naming the changed image_0.png (exit ${status})\n${out}${err}")
  endif()
  # The image as the bake writes it again, for the validator below.
  execute_process(COMMAND ${DQSKIN} bake ${INPUT} -o ${OUT} --format glb --fps 4 --glb-images ${MODE} --quiet --force
                  RESULT_VARIABLE status ERROR_VARIABLE err TIMEOUT 300)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "dqskin bake --force: exit status ${status}\n${err}")
  endif()
  # Sharded: the shard that writes the animation's whole-animation files writes the image, and `dqskin
  # merge` gives the unsharded bake's manifest; shards baked with another --glb-images are refused.
  foreach(shard 0 1)
    execute_process(COMMAND ${DQSKIN} bake ${INPUT} -o ${OUT}_shards --format glb --fps 4 --shard ${shard}/2 --quiet
                    RESULT_VARIABLE status ERROR_VARIABLE err TIMEOUT 300)
    if(NOT status EQUAL 0)
      message(FATAL_ERROR "dqskin bake --shard ${shard}/2: exit status ${status}\n${err}")
    endif()
  endforeach()
  execute_process(COMMAND ${DQSKIN} merge ${OUT}_shards RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
  file(READ ${OUT}_shards/manifest.json merged)
  if(NOT status EQUAL 0 OR NOT merged STREQUAL manifest)
    message(FATAL_ERROR "the merged shards' manifest should be the unsharded bake's (merge exit ${status})\n${out}${err}")
  endif()
  file(REMOVE_RECURSE ${OUT}_shards)
  foreach(shard 0 1)
    list(GET modes ${shard} mode)
    execute_process(COMMAND ${DQSKIN} bake ${INPUT} -o ${OUT}_shards --format glb --fps 4 --shard ${shard}/2 --quiet
                    --glb-images ${mode} RESULT_VARIABLE status ERROR_VARIABLE err TIMEOUT 300)
  endforeach()
  execute_process(COMMAND ${DQSKIN} merge ${OUT}_shards RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
  if(NOT status EQUAL 2 OR NOT err MATCHES "glb_images: \"embed\" here, \"shared\" there")
    message(FATAL_ERROR "merge should refuse shards baked with other --glb-images (exit ${status})\n${out}${err}")
  endif()
  file(REMOVE_RECURSE ${OUT}_shards)
elseif(images)
  message(FATAL_ERROR "no image file expected beside the frames with --glb-images ${MODE}: ${images}")
endif()
if(NOT manifest MATCHES "\"glb_images\": \"${MODE}\"")
  message(FATAL_ERROR "the manifest does not record glb_images ${MODE}")
endif()

if(DEFINED NODE)
  if(NOT EXISTS ${VALIDATOR}/package.json)
    message("SKIP: the glTF-Validator is not installed at ${VALIDATOR} (scripts/install/node_tools.sh)")
    return()
  endif()
  execute_process(COMMAND ${NODE} ${SCRIPT} --validator ${VALIDATOR} ${OUT} RESULT_VARIABLE status
                  OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 300)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "glTF-Validator: exit status ${status}\n${out}${err}")
  endif()
endif()
