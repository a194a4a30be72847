# The newer commands against crafted inputs (scripts/make_hostile_commands.py, docs/SECURITY.md "Every
# command"): report, lint and lint --fix, verify, merge, the diffs and the morph and texture bakes must do
# what bake does with a hostile file: one printable line naming the file, exit 2 (1 when only some inputs
# failed), nothing half-written, memory within --max-memory, no hang. Every case runs under a 4 GiB
# address-space cap (prlimit; in sanitizer builds ASan's largest allocation instead) and a time limit, so
# that a command that would take too much or never return fails instead of swapping or stalling CI.
find_package(Python3 COMPONENTS Interpreter REQUIRED)
set(DQSKIN_HOSTILE_DIR ${CMAKE_CURRENT_BINARY_DIR}/hostile)
set(_hostile_generator ${PROJECT_SOURCE_DIR}/scripts/make_hostile_commands.py)
execute_process(
  COMMAND ${Python3_EXECUTABLE} ${_hostile_generator} ${DQSKIN_HOSTILE_DIR}
  RESULT_VARIABLE _status OUTPUT_VARIABLE _output ERROR_VARIABLE _output)
if(NOT _status STREQUAL "0")
  message(FATAL_ERROR "scripts/make_hostile_commands.py failed (${_status}):\n${_output}")
endif()
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${_hostile_generator}
  ${PROJECT_SOURCE_DIR}/scripts/make_malformed.py ${PROJECT_SOURCE_DIR}/scripts/gltf_builder.py)

# dqskin_limit_test(NAME EXPECTED ARGS ... [TIMEOUT s] [options of dqskin_outcome_case])
# One case, limits.NAME: `dqskin ARGS` run in the generated folder under a 4 GiB address-space cap, with
# TIMEOUT seconds (default 60) for the command. Label "limits".
set(limits_scratch ${CMAKE_CURRENT_BINARY_DIR}/limits)
file(MAKE_DIRECTORY ${limits_scratch})
include(${CMAKE_CURRENT_LIST_DIR}/outcome_test.cmake)
function(dqskin_limit_test name expected)
  cmake_parse_arguments(T "" "TIMEOUT" "" ${ARGN})
  if(NOT DEFINED T_TIMEOUT)
    set(T_TIMEOUT 60)
  endif()
  math(EXPR ctest_timeout "${T_TIMEOUT} + 60")
  dqskin_outcome_case(limits.${name} ${expected} WORKING_DIRECTORY ${DQSKIN_HOSTILE_DIR} LABEL limits
    MEMORY_LIMIT_MB 4096 TIMEOUT ${T_TIMEOUT} CTEST_TIMEOUT ${ctest_timeout} ${T_UNPARSED_ARGUMENTS})
endfunction()

# ---- report ------------------------------------------------------------------------------------------------
# 1,000 clips of a quad: report held every contact sheet and built the page embedding them in one string
# (5.7 GB; 480 MB resident at --max-memory 256M, refused). Sheets are now written as they are drawn and
# the page and report.json as they are made: the whole report fits in 256 MiB.
dqskin_limit_test(report_1000_clips_within_max_memory 0 TIMEOUT 120
  ARGS report report/clips_1000.gltf -o ${limits_scratch}/report_1000 --image-size 96 --max-memory 256M --quiet
  MAX_RSS_MB 400
  PRESENT ${limits_scratch}/report_1000/clips_1000/report.html ${limits_scratch}/report_1000/clips_1000/report.json
          ${limits_scratch}/report_1000/clips_1000/worst_clip999.png)

# A clip of 10^6 s at 1 fps: a million frames of figures. Past the ceiling the report's document was
# destroyed while the refusal unwound, and its destructor allocated (std::terminate: exit 134, two lines,
# a stray sheet). Now one line and nothing written.
dqskin_limit_test(report_clip_1e6_s_refused_in_one_line 2 FOLDER ${limits_scratch}/report_1e6 UNCHANGED
  ARGS report report/clip_1e6.gltf --fps 1 -o ${limits_scratch}/report_1e6 --max-memory 256M --quiet
  ONE_LINE TIMEOUT 120
  STDERR "^dqskin: report/clip_1e6.gltf: needs more memory than --max-memory 256 MiB allows \\(")

# A report is all of its files or none: SIGTERM while the sheet is written, and the leftovers of a
# SIGKILL removed by the next run (app/tests/report_signal.sh).
add_test(NAME limits.report_signal_all_or_nothing COMMAND bash ${PROJECT_SOURCE_DIR}/app/tests/report_signal.sh
  $<TARGET_FILE:dqskin_cli> ${DQSKIN_HOSTILE_DIR}/report/rig_300_joints.glb ${limits_scratch}/report_signal)
set_tests_properties(limits.report_signal_all_or_nothing PROPERTIES LABELS limits TIMEOUT 600
  PASS_REGULAR_EXPRESSION "PASS" FAIL_REGULAR_EXPRESSION "FAIL:")
