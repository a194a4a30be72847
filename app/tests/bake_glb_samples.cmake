# Bakes every rig in testdata/ and every shared model (when present) to glb at 2 fps, each into its own
# folder under OUT, for the glTF-Validator test (app/tests/bake.cmake). Fails on any bake error.
#   cmake -DCOMMAND=dqskin -DTESTDATA=dir -DSHARED=dir -DOUT=dir -P bake_glb_samples.cmake
file(REMOVE_RECURSE ${OUT})
file(GLOB inputs ${TESTDATA}/*.gltf)
if(IS_DIRECTORY ${SHARED})
  file(GLOB_RECURSE shared ${SHARED}/*.glb ${SHARED}/*.gltf)
  list(APPEND inputs ${shared})
else()
  message(STATUS "bake_glb_samples: ${SHARED} is absent; baking the project's rigs only")
endif()
list(SORT inputs)
set(index 0)
foreach(input IN LISTS inputs)
  execute_process(COMMAND ${COMMAND} bake ${input} -o ${OUT}/${index} --format glb --fps 2 --quiet
                  RESULT_VARIABLE status ERROR_VARIABLE err TIMEOUT 300)
  if(NOT status STREQUAL "0")
    message(FATAL_ERROR "dqskin bake ${input}: exit status ${status}\n${err}")
  endif()
  math(EXPR index "${index} + 1")
endforeach()
message(STATUS "bake_glb_samples: baked ${index} inputs into ${OUT}")
