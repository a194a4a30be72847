# Runs `COMMAND ARGS` (a ;-list) and checks what a user of a failing or hostile run relies on: the exit status
# (EXPECTED), stdout (STDOUT_REGEX), stderr (STDERR_REGEX; with ONE_LINE, exactly one line and no control
# character in it), and
# that FOLDER is afterwards exactly as it was before (UNCHANGED: the same entries, hidden ones included, with
# the same bytes; "absent" stays absent). The command has TIMEOUT seconds (default 300): a hang fails.
#
#   cmake -DCOMMAND=dqskin "-DARGS=bake;x.gltf;-o;out" -DEXPECTED=2 [-DSTDOUT_REGEX=...] [-DSTDERR_REGEX=...] [-DONE_LINE=ON]
#         [-DFOLDER=out [-DUNCHANGED=ON] [-DPREPARE=args of a run that must succeed first]
#          [-DALTER=file in FOLDER to overwrite after it] [-DPRESENT=paths] [-DABSENT=paths]]
#         [-DWORKING_DIRECTORY=dir] [-DTIMEOUT=s]
#         [-DMEMORY_LIMIT_MB=n [-DPRLIMIT=path/to/prlimit]] [-DMAX_RSS_MB=n -DPYTHON=python3] -P expect_outcome.cmake
# MEMORY_LIMIT_MB caps the command's address space through prlimit (not in sanitizer builds, whose shadow
# memory needs terabytes of it; there it caps the largest single allocation through ASAN_OPTIONS), so that
# a command that would take far too much fails fast instead of swapping. MAX_RSS_MB fails a run whose
# resident set grew past it (measured by peak_rss.py; callers leave it out in sanitizer builds, where
# ASan's shadow and quarantine are resident too).
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

set(launcher "")
if(DEFINED MAX_RSS_MB)
  string(RANDOM LENGTH 12 token)
  set(rss_file "$ENV{TMPDIR}")
  if(NOT rss_file)
    set(rss_file /tmp)
  endif()
  set(rss_file "${rss_file}/dqskin-peak-rss-${token}.kib")
  set(launcher ${PYTHON} ${CMAKE_CURRENT_LIST_DIR}/peak_rss.py ${rss_file})
endif()
if(DEFINED MEMORY_LIMIT_MB)
  set(ENV{ASAN_OPTIONS} "$ENV{ASAN_OPTIONS}:max_allocation_size_mb=${MEMORY_LIMIT_MB}")
  if(DEFINED PRLIMIT)
    math(EXPR bytes "${MEMORY_LIMIT_MB} * 1048576")
    list(APPEND launcher ${PRLIMIT} --as=${bytes} --)
  endif()
endif()
execute_process(COMMAND ${launcher} ${COMMAND} ${ARGS} WORKING_DIRECTORY ${WORKING_DIRECTORY}
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
if(DEFINED MAX_RSS_MB)
  file(READ "${rss_file}" peak_kib)
  file(REMOVE "${rss_file}")
  string(STRIP "${peak_kib}" peak_kib)
  math(EXPR peak_mb "${peak_kib} / 1024")
  if(peak_mb GREATER MAX_RSS_MB)
    string(APPEND problems "its resident set grew to ${peak_mb} MiB, more than ${MAX_RSS_MB} MiB\n")
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
