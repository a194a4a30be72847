# One model of app/tests/optimize.cmake: optimize INPUT at 0.1 % of its diagonal into OUT, then check the
# output with `dqskin diff` (at the budget the summary states, in scene units, LBS as optimized), with
# `dqskin lint` (no finding the input did not have, no worse an exit status) and with the Khronos validator.
cmake_minimum_required(VERSION 3.25)

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

# lint finds nothing new: every finding of the output (a check at a severity) is one of the input's, and
# the output's exit status is no worse. Counts may differ (a dropped channel is one finding fewer).
function(lint_findings file out_findings out_status)
  execute_process(COMMAND ${DQSKIN} lint --json ${file} RESULT_VARIABLE status OUTPUT_VARIABLE report
    ERROR_VARIABLE err TIMEOUT 120)
  string(JSON n ERROR_VARIABLE problem LENGTH "${report}" files 0 findings)
  if(problem)
    message(FATAL_ERROR "dqskin lint --json ${file}: exit status ${status}, no findings list (${problem})\n${report}${err}")
  endif()
  set(found "")
  if(n GREATER 0)
    math(EXPR last "${n} - 1")
    foreach(i RANGE ${last})
      string(JSON check GET "${report}" files 0 findings ${i} check)
      string(JSON severity GET "${report}" files 0 findings ${i} severity)
      list(APPEND found "${severity}:${check}")
    endforeach()
  endif()
  set(${out_findings} "${found}" PARENT_SCOPE)
  set(${out_status} "${status}" PARENT_SCOPE)
endfunction()
lint_findings("${INPUT}" input_findings input_status)
lint_findings("${OUT}" output_findings output_status)
foreach(finding IN LISTS output_findings)
  if(NOT finding IN_LIST input_findings)
    message(FATAL_ERROR "dqskin lint finds ${finding} in ${OUT}, which the input (${input_findings}) did not have")
  endif()
endforeach()
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
