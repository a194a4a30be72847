# `dqskin lint` on every shared model (.gltf, .glb under DIR): each run ends with exit status 0, 1 or 2 (never
# a crash or a signal), prints its report, and --json is one JSON document. Prints each model's summary
# line. Prints "lint: SKIPPED" when DIR is missing.
#
#   cmake -DDQSKIN=dqskin -DDIR=../shared/testdata -P lint_models.cmake
cmake_minimum_required(VERSION 3.25)
if(NOT IS_DIRECTORY "${DIR}")
  message("lint: SKIPPED: ${DIR} is missing (the shared models are in ../shared/testdata beside the repository)")
  return()
endif()
file(GLOB_RECURSE models "${DIR}/*.gltf" "${DIR}/*.glb")
list(SORT models)
if(NOT models)
  message("lint: SKIPPED: no .gltf or .glb under ${DIR}")
  return()
endif()
foreach(model IN LISTS models)
  execute_process(COMMAND "${DQSKIN}" lint --json "${model}" RESULT_VARIABLE status OUTPUT_VARIABLE out
                  ERROR_VARIABLE err TIMEOUT 300)
  if(NOT status MATCHES "^[012]$")
    message(FATAL_ERROR "dqskin lint ${model}: exit status '${status}'\n${err}")
  endif()
  string(JSON summary ERROR_VARIABLE bad GET "${out}" summary status)
  if(bad)
    message(FATAL_ERROR "dqskin lint --json ${model}: not a report (${bad})\n${out}")
  endif()
  message("${model}: exit ${status}, ${summary}")
endforeach()
