# `dqskin lint --fix` changes how data is stored, not what it means: for FILE, the fixed copy deforms like
# the original over every clip (`dqskin diff` on the CPU reference, within 1e-6 of each clip's diagonal).
# Holds for what dqskin's own sampling and blending already treat alike: merged duplicate joints, sorted
# influences, negated keys (slerp takes the shortest path, Appendix C), unit keys (renormalised when
# sampled). Prints "lint: SKIPPED" when FILE is missing.
#
#   cmake -DDQSKIN=dqskin -DFILE=in.glb -DWORK=folder -P lint_same_deformation.cmake
cmake_minimum_required(VERSION 3.25)
if(NOT EXISTS "${FILE}")
  message("lint: SKIPPED: ${FILE} is missing (the shared models are in ../shared/testdata beside the repository)")
  return()
endif()
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
execute_process(COMMAND "${DQSKIN}" lint --fix "${FILE}" -o "${WORK}/fixed.glb" RESULT_VARIABLE status
                OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
if(NOT status MATCHES "^[01]$" OR NOT EXISTS "${WORK}/fixed.glb")
  message(FATAL_ERROR "dqskin lint --fix ${FILE}: exit status ${status}\n${out}${err}")
endif()
execute_process(COMMAND "${DQSKIN}" diff "${FILE}" "${WORK}/fixed.glb" --backend cpu --relative --fail 1e-6
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 600)
if(NOT status STREQUAL "0")
  message(FATAL_ERROR "the fixed ${FILE} deforms differently (dqskin diff exit status ${status}):\n${out}${err}")
endif()
