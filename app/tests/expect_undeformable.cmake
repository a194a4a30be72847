# A file that parses as glTF but cannot be deformed (malformed/undeformable.txt): the commands that describe
# it read it, the commands that deform refuse it. Fails unless
#   - `COMMAND info FILE` exits with status 0, prints nothing on stderr, and lists a reason matching REGEX
#     under "cannot be deformed" (a line "    REASON");
#   - `COMMAND lint FILE` exits with status 2 and reports the check cannot-deform as an error;
#   - `COMMAND bake FILE -o SCRATCH` exits with status 2, prints exactly one line on stderr,
#     "dqskin: FILE: MESSAGE" with MESSAGE matching REGEX from its start, and creates no SCRATCH.
#
#   cmake -DCOMMAND=path/to/dqskin -DFILE=input.gltf -DREGEX=... -DSCRATCH=dir [-DWORKING_DIRECTORY=dir]
#         -P expect_undeformable.cmake
foreach(var COMMAND FILE REGEX SCRATCH)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "expect_undeformable.cmake: -D${var}=... is required")
  endif()
endforeach()
if(NOT DEFINED WORKING_DIRECTORY)
  set(WORKING_DIRECTORY .)
endif()
set(problems "")

execute_process(COMMAND ${COMMAND} info ${FILE} WORKING_DIRECTORY ${WORKING_DIRECTORY}
  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
if(NOT status STREQUAL "0" OR NOT err STREQUAL "")
  string(APPEND problems "info: exit status ${status} (expected 0), stderr:\n${err}\n")
endif()
string(REGEX REPLACE "\\$$" "" line_regex "${REGEX}")  # the reason is one line of several: no '$' inside
if(status STREQUAL "0" AND NOT out MATCHES "\n  cannot be deformed [^\n]*:\n(    [^\n]*\n)*    (${line_regex})\n")
  string(APPEND problems "info does not list a reason matching '${REGEX}' under 'cannot be deformed':\n${out}\n")
endif()

execute_process(COMMAND ${COMMAND} lint ${FILE} WORKING_DIRECTORY ${WORKING_DIRECTORY}
  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
if(NOT status STREQUAL "2" OR NOT out MATCHES "  error +cannot-deform \\([0-9]+\\): ")
  string(APPEND problems "lint: exit status ${status} (expected 2 with an error cannot-deform), stdout:\n${out}stderr:\n${err}\n")
endif()

file(REMOVE_RECURSE "${SCRATCH}")
execute_process(COMMAND ${COMMAND} bake ${FILE} -o ${SCRATCH} WORKING_DIRECTORY ${WORKING_DIRECTORY}
  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
set(prefix "dqskin: ${FILE}: ")
string(LENGTH "${prefix}" prefix_length)
string(SUBSTRING "${err}" 0 ${prefix_length} head)
if(NOT status STREQUAL "2")
  string(APPEND problems "bake: exit status '${status}', expected 2\n")
endif()
if(NOT head STREQUAL prefix OR NOT err MATCHES "^[^\n]*\n$")
  string(APPEND problems "bake: stderr is not one line starting with '${prefix}'\n")
else()
  string(SUBSTRING "${err}" ${prefix_length} -1 message)
  string(REGEX REPLACE "\n$" "" message "${message}")
  if(NOT message MATCHES "^(${REGEX})")
    string(APPEND problems "bake: the message does not match the regex '${REGEX}'\n")
  endif()
endif()
if(EXISTS "${SCRATCH}")
  string(APPEND problems "bake: ${SCRATCH} was created\n")
endif()

if(NOT problems STREQUAL "")
  message(FATAL_ERROR "${FILE}:\n${problems}bake's stderr was:\n${err}")
endif()
