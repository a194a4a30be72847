# The browser check of one report page (lib/CMakeLists.txt), at test time: runs report_check.mjs on PAGE and
# expects it to pass (EXPECT=pass), or to fail (exit 1) with a line matching PROBLEM (EXPECT=fail): a check
# that passed a deliberately broken page would be no check.
# Prints "report_check: SKIPPED: <why>" (CTest's SKIP_REGULAR_EXPRESSION) without Node.js or Chromium.
#
#   cmake -DNODE=node -DCHROMIUM=chromium -DSCRIPT=report_check.mjs -DPAGE=dir -DEXPECT=pass|fail
#         [-DPROBLEM=regex] -P report_check.cmake
cmake_minimum_required(VERSION 3.25)

foreach(need NODE CHROMIUM)
  if("${${need}}" STREQUAL "" OR "${${need}}" MATCHES "NOTFOUND$" OR NOT EXISTS "${${need}}")
    message("report_check: SKIPPED: ${need} '${${need}}' is missing (Chromium and Node.js: scripts/install/deps.sh)")
    return()
  endif()
endforeach()
execute_process(COMMAND "${NODE}" "${SCRIPT}" --chromium "${CHROMIUM}" "${PAGE}"
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 100)
message("${out}${err}")
if(EXPECT STREQUAL "pass")
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "report_check found problems in ${PAGE} (exit ${status})")
  endif()
elseif(NOT status EQUAL 1)
  message(FATAL_ERROR "report_check passed a deliberately broken page, or could not run (exit ${status})")
elseif(NOT out MATCHES "${PROBLEM}")
  message(FATAL_ERROR "report_check failed on ${PAGE}, but without naming the breakage ('${PROBLEM}')")
endif()
