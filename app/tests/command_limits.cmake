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

# ---- verify and merge ----------------------------------------------------------------------------------------
# 400,000 files listed (none there): verify took 32 s and merge 58 s, 95 s and 77 s on a busy machine, for the
# JSON parser's depth callback searched the whole outputs list after each entry. Each now names the problems
# within 20 s: verify every file, merge the first 20 and a count, writing nothing.
dqskin_limit_test(verify_400k_entries 2 TIMEOUT 20
  ARGS verify verify/entries_400k
  ONE_LINE STDERR "^verify/entries_400k: 400000 files \\(0 bytes\\) listed by manifest.shard-0-of-2.json, manifest.shard-1-of-2.json: 400000 problems\n$")
dqskin_limit_test(merge_400k_entries 2 TIMEOUT 20
  ARGS merge verify/entries_400k
  ABSENT ${DQSKIN_HOSTILE_DIR}/verify/entries_400k/manifest.json
  STDERR "dqskin: verify/entries_400k: merge refused, nothing written \\(400000 problems\\)\n$")
# Past --max-memory, the one line names the manifest being read, or the folder when checking its files
# took the memory (it said "needs more memory than --max-memory" without a file, or ended in std::terminate:
# nlohmann allocates to free a document, which a ceiling nearly reached refused in a destructor).
dqskin_limit_test(verify_400k_entries_within_max_memory 2
  ARGS verify verify/entries_400k --max-memory 64M --quiet
  ONE_LINE MAX_RSS_MB 500
  STDERR "^dqskin: verify/entries_400k/manifest.shard-0-of-2.json: needs more memory than --max-memory 64.0 MiB allows \\(")
dqskin_limit_test(verify_400k_entries_files_within_max_memory 2
  ARGS verify verify/entries_400k --max-memory 350M --quiet
  ONE_LINE MAX_RSS_MB 800
  STDERR "^dqskin: verify/entries_400k: needs more memory than --max-memory 350 MiB allows \\(")
dqskin_limit_test(merge_400k_entries_within_max_memory 2
  ARGS merge verify/entries_400k --max-memory 350M --quiet
  ONE_LINE MAX_RSS_MB 800 ABSENT ${DQSKIN_HOSTILE_DIR}/verify/entries_400k/manifest.json
  STDERR "^dqskin: verify/entries_400k: needs more memory than --max-memory 350 MiB allows \\(")
# One listed path 20,000 folders deep: verify split every ancestor's path into its parts and never returned.
dqskin_limit_test(verify_deep_path 2 TIMEOUT 15
  ARGS verify verify/deep_path --quiet
  STDOUT "^verify/deep_path/o/a/a/a/[a/]*f: missing \\(listed in manifest.json\\)\n$")
# manifest.shard-0-of-999999.json alone: 999,998 lines, one per missing shard; consecutive ones are one now.
dqskin_limit_test(verify_many_missing_shards 2 TIMEOUT 15
  ARGS verify verify/many_shards --quiet
  STDOUT "^verify/many_shards/manifest.shard-1-of-999999.json: missing, and so are the manifests up to manifest.shard-999998-of-999999.json: [^\n]*\n$")
# Hostile manifests are one problem each, naming the manifest, and exit 2 (merge: the problem, and its
# refusal with the folder as it was).
foreach(case truncated huge_numbers deep_nesting dot_dot absolute nul_name)
  dqskin_limit_test(verify_manifest_${case} 2 TIMEOUT 15
    ARGS verify verify/${case} --quiet
    STDOUT "^verify/${case}/manifest.json: the manifest [^\n]*\n$")
  dqskin_limit_test(merge_manifest_${case} 2 TIMEOUT 15
    ARGS merge verify/${case}
    STDERR "^dqskin: verify/${case}/manifest.json: the manifest [^\n]*\n")
endforeach()
dqskin_limit_test(verify_symlink_not_followed 2 TIMEOUT 15
  ARGS verify verify/symlink --quiet
  STDOUT "^verify/symlink/o: is a symbolic link, which verify does not follow\nverify/symlink/o/passwd: lies behind a symbolic link")
dqskin_limit_test(verify_conflicting_entries 2 TIMEOUT 15
  ARGS verify verify/conflict --quiet
  STDOUT "^verify/conflict/o/a: listed differently by manifest.json and manifest.json\n")

# SIGTERM and SIGINT: one line, the process ended by the signal, the folder as it was (merge wrote its
# manifest without any handler: a signal left the temporary, or a half-swapped folder).
add_test(NAME limits.merge_and_verify_stopped_by_signals
  COMMAND bash ${PROJECT_SOURCE_DIR}/app/tests/interrupt_merge.sh $<TARGET_FILE:dqskin_cli> ${DQSKIN_HOSTILE_DIR}
    ${limits_scratch}/interrupt_merge)
set_tests_properties(limits.merge_and_verify_stopped_by_signals PROPERTIES TIMEOUT 300 LABELS limits)
