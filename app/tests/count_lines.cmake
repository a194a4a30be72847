# Runs `COMMAND ARGS` (a ;-list) and counts the lines of its stdout and stderr together that match REGEX:
# fails unless the exit status is EXPECTED and the count is COUNT. For messages that must appear exactly
# once (a notice per file, not per node) or not at all.
#
#   cmake -DCOMMAND=dqskin "-DARGS=info;x.gltf" -DEXPECTED=0 -DREGEX=regex -DCOUNT=1 -P count_lines.cmake
cmake_minimum_required(VERSION 3.25)
execute_process(COMMAND ${COMMAND} ${ARGS} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 300)
if(NOT status STREQUAL "${EXPECTED}")
  message(FATAL_ERROR "${COMMAND} ${ARGS}: exit status ${status}, expected ${EXPECTED}\n${out}${err}")
endif()
string(REPLACE ";" "," text "${out}${err}")  # a ; in the output would split the list of lines
string(REPLACE "\n" ";" lines "${text}")
set(count 0)
foreach(line IN LISTS lines)
  if(line MATCHES "${REGEX}")
    math(EXPR count "${count} + 1")
  endif()
endforeach()
if(NOT count EQUAL COUNT)
  message(FATAL_ERROR "${COMMAND} ${ARGS}: ${count} lines match '${REGEX}', expected ${COUNT}\n${out}${err}")
endif()
