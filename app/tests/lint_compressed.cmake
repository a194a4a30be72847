# `dqskin lint` on a file that gltfpack compressed (EXT_meshopt_compression, quantized attributes): lint
# reads it (decoded as the loader decodes it); --fix refuses it with one line naming the file and the
# extension, prints the input's report, exits 2 and writes nothing. Prints "lint: SKIPPED" without gltfpack.
#
#   cmake -DDQSKIN=dqskin -DTOOLS=node_modules/.bin -DFILE=in.gltf -DWORK=folder -P lint_compressed.cmake
cmake_minimum_required(VERSION 3.25)
macro(skip why)
  message("lint: SKIPPED: ${why}")
  return()
endmacro()
include(${CMAKE_CURRENT_LIST_DIR}/npm_tool.cmake)
npm_tool_or_skip(gltfpack)
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(packed "${WORK}/packed.glb")
execute_process(COMMAND "${program}" -i "${FILE}" -o "${packed}" -c RESULT_VARIABLE status OUTPUT_QUIET
                ERROR_VARIABLE err TIMEOUT 120)
if(NOT status STREQUAL "0")
  message(FATAL_ERROR "gltfpack -c ${FILE}: exit status ${status}: ${err}")
endif()
execute_process(COMMAND "${DQSKIN}" lint --json "${packed}" RESULT_VARIABLE status OUTPUT_VARIABLE out
                ERROR_VARIABLE err TIMEOUT 120)
string(JSON problem ERROR_VARIABLE no_problem GET "${out}" files 0 problem)  # absent when it was read
if(NOT status MATCHES "^[01]$" OR NOT no_problem)
  message(FATAL_ERROR "dqskin lint ${packed}: exit status ${status}, should be read\n${out}${err}")
endif()
execute_process(COMMAND "${DQSKIN}" lint --fix "${packed}" -o "${WORK}/fixed.glb" RESULT_VARIABLE status
                OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
if(NOT status STREQUAL "2" OR NOT err MATCHES "^dqskin: [^\n]*packed.glb: --fix: it uses EXT_meshopt_compression[^\n]*\n$"
   OR NOT out MATCHES "packed.glb: " OR EXISTS "${WORK}/fixed.glb")
  message(FATAL_ERROR "dqskin lint --fix ${packed}: exit status ${status}\nstdout: ${out}\nstderr: ${err}")
endif()
