# Runs COMMAND with ARGS (a ;-list) and fails unless it exits with EXPECTED.
# CTest's WILL_FAIL only knows "non-zero"; dqskin's exit codes carry meaning (see README).
execute_process(COMMAND ${COMMAND} ${ARGS} RESULT_VARIABLE status OUTPUT_QUIET ERROR_QUIET)
if(NOT status STREQUAL EXPECTED)
  message(FATAL_ERROR "${COMMAND} ${ARGS}: exit status ${status}, expected ${EXPECTED}")
endif()
