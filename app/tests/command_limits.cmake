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
# 1,000 clips of a quad: report held every contact sheet and the page embedding them (5.7 GB at
# --max-memory 256M). Under the ceiling it is refused with the figures, resident set and output folder
# as they were.
dqskin_limit_test(report_1000_clips_within_max_memory 2 FOLDER ${limits_scratch}/report_1000 UNCHANGED
  ARGS report report/clips_1000.gltf -o ${limits_scratch}/report_1000 --max-memory 256M --quiet
  ONE_LINE MAX_RSS_MB 700
  STDERR "^dqskin: report/clips_1000.gltf: needs more memory than --max-memory 256 MiB allows \\(")

# ---- lint ----------------------------------------------------------------------------------------------------
# A chain of 200,000 joints: lint walked from every joint up to its root and the skeleton (minutes); now
# about as long as loading the file (`dqskin info`: 2 s). --fix was as quadratic in the skeleton check;
# it reads the file four times (lint, the fix's data, the fixed .glb's JSON, lint of the fixed file):
# 7.5 s alone, 16 s beside two other tests on two cores, hence its 60 s.
file(MAKE_DIRECTORY ${limits_scratch}/lint)
dqskin_limit_test(lint_200k_joint_chain 1 TIMEOUT 30
  ARGS lint lint/chain_200k.gltf --max-memory 1G MAX_RSS_MB 1024
  STDOUT "^lint/chain_200k.gltf: warning\n  info    unused-joint \\(200000\\)")
dqskin_limit_test(lint_fix_200k_joint_chain 1 TIMEOUT 60
  ARGS lint --fix lint/chain_200k.gltf -o ${limits_scratch}/lint/chain_200k.fixed.glb --max-memory 1G MAX_RSS_MB 1024
  STDERR "^dqskin: lint: wrote [^\n]*/chain_200k.fixed.glb "
  STDOUT "\n[^\n]*chain_200k.fixed.glb: warning\n  info    unused-joint \\(200000\\)")
# 1,000,000 vertices without weight and 50,000 joints: --fix compared each vertex with every joint for the
# nearest one (over a minute); a k-d tree answers each in about log(joints).
dqskin_limit_test(lint_fix_unweighted_vertices_50k_joints 1 TIMEOUT 30
  ARGS lint --fix lint/unweighted_50k.gltf -o ${limits_scratch}/lint/unweighted_50k.fixed.glb --max-memory 1G
  MAX_RSS_MB 1024 STDERR "^dqskin: lint: wrote [^\n]*/unweighted_50k.fixed.glb "
  STDOUT "\n[^\n]*unweighted_50k.fixed.glb: warning\n")
# 4,000,000 vertices without weight in a 3 KB file: lint fits in 640 MiB, --fix did not, and the
# ceiling's refusal escaped as "dqskin: needs more memory ..." without the file (at the default 2 GiB
# too, for 16,000,000 vertices). --fix now estimates what it will hold before it starts and refuses in one
# line naming the file; the report of the input is still printed, and nothing is written.
dqskin_limit_test(lint_fix_4m_vertices_within_max_memory 2 TIMEOUT 60
  ARGS lint --fix lint/unweighted_4m.gltf -o ${limits_scratch}/lint/unweighted_4m.fixed.glb --max-memory 640M
  ONE_LINE MAX_RSS_MB 800 ABSENT ${limits_scratch}/lint/unweighted_4m.fixed.glb
  STDOUT "^lint/unweighted_4m.gltf: error\n"
  STDERR "^dqskin: lint/unweighted_4m.gltf: --fix: rewriting the influences of 4000000 vertices needs about [^\n]*, more than --max-memory 640 MiB\n$")
dqskin_limit_test(lint_4m_vertices_within_max_memory 2 TIMEOUT 60
  ARGS lint lint/unweighted_4m.gltf --max-memory 200M ONE_LINE MAX_RSS_MB 400
  STDERR "^dqskin: lint/unweighted_4m.gltf: loading it needs about [^\n]*, more than --max-memory 200 MiB\n$")
