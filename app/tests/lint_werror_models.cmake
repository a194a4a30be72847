# `dqskin lint --werror` on the shared models whose rigs are legal: each exits 0 (information only). Prints
# "lint: SKIPPED" when DIR is missing. MODELS: paths under DIR, a ;-list.
#
#   cmake -DDQSKIN=dqskin -DDIR=../shared/testdata "-DMODELS=Fox/Fox.glb;..." -P lint_werror_models.cmake
cmake_minimum_required(VERSION 3.25)
if(NOT IS_DIRECTORY "${DIR}")
  message("lint: SKIPPED: ${DIR} is missing (the shared models are in ../shared/testdata beside the repository)")
  return()
endif()
set(failed "")
foreach(model IN LISTS MODELS)
  if(NOT EXISTS "${DIR}/${model}")
    message("lint: ${model} is missing; not checked")
    continue()
  endif()
  execute_process(COMMAND "${DQSKIN}" lint --werror "${DIR}/${model}" RESULT_VARIABLE status OUTPUT_VARIABLE out
                  ERROR_VARIABLE err TIMEOUT 300)
  message("${model}: exit ${status}")
  if(NOT status STREQUAL "0")
    string(APPEND failed "${model} (exit ${status}):\n${out}${err}\n")
  endif()
endforeach()
if(failed)
  message(FATAL_ERROR "lint --werror fails legal rigs:\n${failed}")
endif()
