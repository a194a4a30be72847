# Runs `COMMAND diff ARGS` (a ;-list) and passes on exit status 0 (all pass) or 1 (warnings, no failure),
# printing the report either way, so that `ctest -V` shows the metrics of every golden image.
#   cmake -DCOMMAND=dqskin "-DARGS=testdata/golden;build/golden;--fail;0.02" -P golden_diff.cmake
execute_process(COMMAND ${COMMAND} diff ${ARGS} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 300)
message("${out}${err}")
if(NOT status EQUAL 0 AND NOT status EQUAL 1)
  message(FATAL_ERROR "dqskin diff ${ARGS}: exit status ${status}")
endif()
