# Runs `COMMAND info FILE` and fails unless it exits with status 2 (input error), prints nothing on
# stdout, and prints exactly one line on stderr: "dqskin: FILE: MESSAGE" with MESSAGE matching REGEX
# from its start (CMake regex syntax). CTest's PASS_REGULAR_EXPRESSION cannot check the exit status, so
# this script checks both. With REGEX unset it checks the opposite: exit status 0, nothing on stderr; and
# with WARNING set, that the text output lists a warning matching it (a line "    WARNING").
#
#   cmake -DCOMMAND=path/to/dqskin -DFILE=input.gltf [-DREGEX=... | -DWARNING=...] [-DWORKING_DIRECTORY=dir]
#         [-DPRLIMIT=path/to/prlimit -DMEMORY_LIMIT_MB=n] -P expect_error.cmake
#
# A broken input may make the loader allocate far too much; MEMORY_LIMIT_MB caps the address space
# through prlimit (not for sanitizer builds, whose shadow memory needs terabytes of it) and, for those,
# the largest single allocation through ASAN_OPTIONS, so such a test fails fast instead of swapping.
foreach(var COMMAND FILE)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "expect_error.cmake: -D${var}=... is required")
  endif()
endforeach()

set(launcher "")
if(DEFINED MEMORY_LIMIT_MB)
  set(ENV{ASAN_OPTIONS} "$ENV{ASAN_OPTIONS}:max_allocation_size_mb=${MEMORY_LIMIT_MB}")
  if(DEFINED PRLIMIT)
    math(EXPR bytes "${MEMORY_LIMIT_MB} * 1048576")
    set(launcher ${PRLIMIT} --as=${bytes} --)
  endif()
endif()
if(NOT DEFINED WORKING_DIRECTORY)
  set(WORKING_DIRECTORY .)
endif()
execute_process(COMMAND ${launcher} ${COMMAND} info ${FILE} WORKING_DIRECTORY ${WORKING_DIRECTORY}
  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)

if(NOT DEFINED REGEX)
  if(NOT status STREQUAL "0" OR NOT err STREQUAL "")
    message(FATAL_ERROR "${FILE}: expected it to load (exit status 0, empty stderr), "
                        "got exit status ${status} and stderr:\n${err}")
  endif()
  if(DEFINED WARNING AND NOT out MATCHES "\n    (${WARNING})\n")
    message(FATAL_ERROR "${FILE}: expected a warning matching '${WARNING}', got:\n${out}")
  endif()
  return()
endif()

set(problems "")
# One printable line: no control character but the final newline (dqskin escapes them as \x1b, \n).
string(ASCII 1 2 3 4 5 6 7 8 9 11 12 13 14 15 16 17 18 19 20 21 22 23 24 25 26 27 28 29 30 31 127 controls)
if(err MATCHES "[${controls}]")
  string(APPEND problems "stderr holds a control character\n")
endif()
if(NOT status STREQUAL "2")
  string(APPEND problems "exit status is '${status}', expected 2\n")
endif()
if(NOT out STREQUAL "")
  string(APPEND problems "stdout is not empty\n")
endif()
set(prefix "dqskin: ${FILE}: ")
string(LENGTH "${prefix}" prefix_length)
string(SUBSTRING "${err}" 0 ${prefix_length} head)
if(NOT head STREQUAL prefix)
  string(APPEND problems "stderr does not start with '${prefix}'\n")
elseif(NOT err MATCHES "^[^\n]*\n$")
  string(APPEND problems "stderr is not exactly one line\n")
else()
  string(SUBSTRING "${err}" ${prefix_length} -1 message)
  string(REGEX REPLACE "\n$" "" message "${message}")
  if(NOT message MATCHES "^(${REGEX})")
    string(APPEND problems "the message does not match the regex '${REGEX}'\n")
  endif()
endif()
if(NOT problems STREQUAL "")
  message(FATAL_ERROR "${FILE}:\n${problems}stderr was:\n${err}stdout was:\n${out}")
endif()
