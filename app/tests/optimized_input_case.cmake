# One optimizer's output read by every command (app/tests/optimized_inputs.cmake), at test time: makes B
# from the model A with TOOL (an npm optimizer in TOOLS), then `dqskin info B`, `dqskin bake B` (glb and ply
# of one frame) and `dqskin render B` of frame FRAME must exit 0, and B's render must match A's within
# --fail 0.05 --failpercent 2: quantized positions and filtered normals move a few silhouette pixels
# (0.05 to 0.6% of them on CesiumMan), while a texture read without its KHR_texture_transform, or
# geometry decoded wrongly, changes several percent.
#
#   cmake -DDQSKIN=dqskin -DWORK=folder -DA=model.glb -DTOOL=gltfpack|gltf-transform -DTOOLS=node_modules/.bin
#         "-DTOOL_ARGS=arguments, with <A> and <B> for the files" -DFRAME=n -P optimized_input_case.cmake
# Prints "optimized_input: SKIPPED: <why>" when A or the tool is missing, or the tool cannot start.
cmake_minimum_required(VERSION 3.25)

macro(skip why)
  message("optimized_input: SKIPPED: ${why}")
  return()
endmacro()
include(${CMAKE_CURRENT_LIST_DIR}/npm_tool.cmake)

if(NOT EXISTS "${A}")
  skip("${A} is missing (the shared models are in ../shared/testdata beside the repository)")
endif()
npm_tool_or_skip(${TOOL})

file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(B "${WORK}/b.glb")
list(TRANSFORM TOOL_ARGS REPLACE "^<A>$" "${A}")
list(TRANSFORM TOOL_ARGS REPLACE "^<B>$" "${B}")
execute_process(COMMAND "${program}" ${TOOL_ARGS} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 300)
if(NOT status STREQUAL "0" OR NOT EXISTS "${B}")
  message(FATAL_ERROR "${TOOL} ${TOOL_ARGS} failed (${status}):\n${out}${err}")
endif()

# Runs dqskin with the arguments; fails the test unless it exits 0.
function(dqskin_ok)
  execute_process(COMMAND "${DQSKIN}" ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 300)
  if(NOT status STREQUAL "0")
    string(REPLACE ";" " " line "${ARGN}")
    message(FATAL_ERROR "dqskin ${line}: exit status ${status}\n${out}${err}")
  endif()
endfunction()

dqskin_ok(info "${B}")
dqskin_ok(bake "${B}" --format glb,ply --frames ${FRAME}:${FRAME} -o "${WORK}/bake")
foreach(side a b)
  set(input "${A}")
  if(side STREQUAL "b")
    set(input "${B}")
  endif()
  # Both under the same name, so that render writes the same relative path for each.
  file(MAKE_DIRECTORY "${WORK}/${side}")
  file(COPY_FILE "${input}" "${WORK}/${side}/model.glb")
  dqskin_ok(render "${WORK}/${side}/model.glb" --frames ${FRAME}:${FRAME} -o "${WORK}/render_${side}")
endforeach()
dqskin_ok(diff "${WORK}/render_a" "${WORK}/render_b" --fail 0.05 --failpercent 2 --warn 1)
message("optimized_input: ${TOOL} ${TOOL_ARGS}: info, bake and render read it; its render matches the original's")
