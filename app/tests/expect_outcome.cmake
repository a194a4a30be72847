# Runs `COMMAND ARGS` (a ;-list) and checks what a user of a failing or hostile run relies on: the exit status
# (EXPECTED), stdout (STDOUT_REGEX), stderr (STDERR_REGEX; with ONE_LINE, exactly one line and no control
# character in it), and
# that FOLDER is afterwards exactly as it was before (UNCHANGED: the same entries, hidden ones included, with
# the same bytes; "absent" stays absent). The command has TIMEOUT seconds (default 300): a hang fails.
#
#   cmake -DCOMMAND=dqskin "-DARGS=bake;x.gltf;-o;out" -DEXPECTED=2 [-DSTDOUT_REGEX=...] [-DSTDERR_REGEX=...] [-DONE_LINE=ON]
#         [-DFOLDER=out [-DUNCHANGED=ON] [-DPREPARE=args of a run that must succeed first]
#          [-DALTER=file in FOLDER to overwrite after it] [-DPRESENT=paths] [-DABSENT=paths]]
#         [-DWORKING_DIRECTORY=dir] [-DTIMEOUT=s] -P expect_outcome.cmake
# Included by another script with these variables set (geometry_diff_case.cmake), it leaves the run's
# status, out (stdout) and err (stderr) set for further checks.
if(NOT DEFINED TIMEOUT)
  set(TIMEOUT 300)
endif()
if(NOT DEFINED WORKING_DIRECTORY)
  set(WORKING_DIRECTORY .)
endif()

# Every entry under FOLDER with its SHA-256 ("absent" when there is no FOLDER).
function(snapshot out)
  if(NOT EXISTS "${FOLDER}")
    set(${out} "absent" PARENT_SCOPE)
    return()
  endif()
  file(GLOB_RECURSE entries LIST_DIRECTORIES true RELATIVE "${FOLDER}" "${FOLDER}/*")
  list(SORT entries)
  set(text "")
  foreach(e IN LISTS entries)
    if(IS_DIRECTORY "${FOLDER}/${e}")
      string(APPEND text "${e}/\n")
    else()
      file(SHA256 "${FOLDER}/${e}" hash)
      string(APPEND text "${e} ${hash}\n")
    endif()
  endforeach()
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

if(DEFINED FOLDER)
  file(REMOVE_RECURSE "${FOLDER}")
  if(DEFINED PREPARE)
    execute_process(COMMAND ${COMMAND} ${PREPARE} WORKING_DIRECTORY ${WORKING_DIRECTORY}
      RESULT_VARIABLE status ERROR_VARIABLE err OUTPUT_QUIET TIMEOUT ${TIMEOUT})
    if(NOT status STREQUAL "0")
      message(FATAL_ERROR "the preparing run failed (${status}):\n${err}")
    endif()
  endif()
  if(DEFINED ALTER)
    file(WRITE "${FOLDER}/${ALTER}" "altered by the test\n")
  endif()
  snapshot(before)
endif()

execute_process(COMMAND ${COMMAND} ${ARGS} WORKING_DIRECTORY ${WORKING_DIRECTORY}
  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT ${TIMEOUT})

set(problems "")
if(NOT status STREQUAL EXPECTED)
  string(APPEND problems "exit status '${status}', expected ${EXPECTED}\n")
endif()
if(DEFINED STDOUT_REGEX AND NOT out MATCHES "${STDOUT_REGEX}")
  string(APPEND problems "stdout does not match ${STDOUT_REGEX}\n")
endif()
if(DEFINED STDERR_REGEX AND NOT err MATCHES "${STDERR_REGEX}")
  string(APPEND problems "stderr does not match ${STDERR_REGEX}\n")
endif()
if(ONE_LINE)
  string(ASCII 1 2 3 4 5 6 7 8 9 11 12 13 14 15 16 17 18 19 20 21 22 23 24 25 26 27 28 29 30 31 127 controls)
  if(NOT err MATCHES "^[^\n]*\n$")
    string(APPEND problems "stderr is not exactly one line\n")
  elseif(err MATCHES "[${controls}]")
    string(APPEND problems "stderr holds a control character\n")
  endif()
endif()
if(DEFINED FOLDER AND UNCHANGED)
  snapshot(after)
  if(NOT after STREQUAL before)
    string(APPEND problems "${FOLDER} changed:\nbefore:\n${before}after:\n${after}")
  endif()
endif()
foreach(p IN LISTS PRESENT)
  if(NOT EXISTS "${p}")
    string(APPEND problems "${p} is missing\n")
  endif()
endforeach()
foreach(p IN LISTS ABSENT)
  if(EXISTS "${p}")
    string(APPEND problems "${p} exists\n")
  endif()
endforeach()
if(problems)
  message(FATAL_ERROR "${COMMAND} ${ARGS}:\n${problems}stdout:\n${out}\nstderr:\n${err}")
endif()
