# One model of app/tests/optimize.cmake: optimize INPUT at 0.1 % of its diagonal into OUT, then check the
# output with `dqskin diff` (at the budget the summary states, in scene units, LBS as optimized), with
# `dqskin lint` (no worse an exit status than the input's) and with the Khronos validator.
if(NOT EXISTS "${INPUT}")
  message("optimize_case: SKIPPED: ${INPUT} is absent (the shared test models are not beside the checkout)")
  return()
endif()
get_filename_component(folder "${OUT}" DIRECTORY)
file(MAKE_DIRECTORY "${folder}")
file(REMOVE "${OUT}")
execute_process(COMMAND ${DQSKIN} optimize ${INPUT} -o ${OUT} --max-error 0.1% --json
  RESULT_VARIABLE status OUTPUT_VARIABLE summary ERROR_VARIABLE err TIMEOUT 240)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "dqskin optimize ${INPUT}: exit status ${status}\n${err}")
endif()
string(JSON budget GET "${summary}" budget)
string(JSON before GET "${summary}" animation_bytes_before)
string(JSON after GET "${summary}" animation_bytes_after)
message("optimize ${INPUT}: budget ${budget}, animation data ${before} -> ${after} bytes")
if(after GREATER before)
  message(FATAL_ERROR "the animation data grew: ${before} -> ${after} bytes")
endif()

# The diff's --fail is a distance in scene units; the budget plus float rounding of the two deformations.
execute_process(COMMAND ${DQSKIN} diff ${INPUT} ${OUT} --mode lbs --fail ${budget} --warn ${budget}
  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 240)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "dqskin diff ${INPUT} ${OUT} --fail ${budget}: exit status ${status}\n${out}${err}")
endif()

foreach(file IN ITEMS "${INPUT}" "${OUT}")
  execute_process(COMMAND ${DQSKIN} lint ${file} RESULT_VARIABLE lint_status OUTPUT_QUIET ERROR_QUIET TIMEOUT 120)
  list(APPEND lint_statuses ${lint_status})
endforeach()
list(GET lint_statuses 0 input_status)
list(GET lint_statuses 1 output_status)
if(output_status GREATER input_status)
  message(FATAL_ERROR "dqskin lint: the output's exit status ${output_status} is worse than the input's ${input_status}")
endif()

if(NOT NODE OR NOT EXISTS "${VALIDATOR}/package.json")
  message(FATAL_ERROR "the glTF-Validator is not installed at ${VALIDATOR} (run scripts/install/node_tools.sh)")
endif()
execute_process(COMMAND ${NODE} ${SCRIPTS}/check/validate_gltf.mjs --validator ${VALIDATOR} ${OUT}
  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "the glTF-Validator found errors in ${OUT}:\n${out}${err}")
endif()
