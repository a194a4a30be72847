# The browser check of `dqskin diff --html` (app/tests/diff.cmake), at test time: makes the page of A
# against B with ARGS (a ;-list of extra flags) into WORK/page and the JSON report beside it, then runs
# diff_page_check.mjs on them and expects no problem. Prints "diff_page_check: SKIPPED: <why>" (CTest's
# SKIP_REGULAR_EXPRESSION) without Node.js or Chromium.
#
#   cmake -DDQSKIN=dqskin -DNODE=node -DCHROMIUM=chromium -DSCRIPT=diff_page_check.mjs -DA=dir -DB=dir
#         [-DARGS=--metric;flip] -DWORK=dir -P diff_page_check.cmake
# For a geometric diff, B may be made from A first by scripts/testdata/make_diff_cases.py:
#         -DPYTHON=python3 -DMAKE_SCRIPT=make_diff_cases.py -DMAKE=rotate-key;--joint;elbow -DB=WORK/b.gltf
cmake_minimum_required(VERSION 3.25)

foreach(need NODE CHROMIUM)
  if("${${need}}" STREQUAL "" OR "${${need}}" MATCHES "NOTFOUND$" OR NOT EXISTS "${${need}}")
    message("diff_page_check: SKIPPED: ${need} '${${need}}' is missing (Chromium and Node.js: scripts/install/deps.sh)")
    return()
  endif()
endforeach()
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
if(DEFINED MAKE)
  list(POP_FRONT MAKE make_command)
  execute_process(COMMAND "${PYTHON}" "${MAKE_SCRIPT}" ${make_command} "${A}" "${B}" ${MAKE}
                  RESULT_VARIABLE status OUTPUT_VARIABLE made ERROR_VARIABLE err TIMEOUT 100)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "make_diff_cases.py ${make_command} failed (${status}):\n${made}${err}")
  endif()
endif()
execute_process(COMMAND "${DQSKIN}" diff "${A}" "${B}" ${ARGS} --html "${WORK}/page" --json
                OUTPUT_FILE "${WORK}/report.json" ERROR_VARIABLE err RESULT_VARIABLE status TIMEOUT 100)
if(NOT status MATCHES "^[012]$" OR NOT EXISTS "${WORK}/page/index.html")
  message(FATAL_ERROR "dqskin diff --html did not make its page (exit ${status}): ${err}")
endif()
execute_process(COMMAND "${NODE}" "${SCRIPT}" --chromium "${CHROMIUM}" --shot "${WORK}/shot.png" "${WORK}/page"
                        "${WORK}/report.json"
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 100)
message("${out}${err}")
if(NOT status EQUAL 0)
  message(FATAL_ERROR "diff_page_check found problems in ${WORK}/page (exit ${status})")
endif()
