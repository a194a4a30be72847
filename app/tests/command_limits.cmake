# The newer commands against crafted inputs (scripts/testdata/make_hostile_commands.py, docs/SECURITY.md "Every
# command"): report, lint and lint --fix, verify, merge, the diffs and the morph and texture bakes must do
# what bake does with a hostile file: one printable line naming the file, exit 2 (1 when only some inputs
# failed), nothing half-written, memory within --max-memory, no hang. Every case runs under a 4 GiB
# address-space cap (prlimit; in sanitizer builds ASan's largest allocation instead) and a time limit, so
# that a command that would take too much or never return fails instead of swapping or stalling CI.
find_package(Python3 COMPONENTS Interpreter REQUIRED)
set(DQSKIN_HOSTILE_DIR ${CMAKE_CURRENT_BINARY_DIR}/hostile)
set(_hostile_generator ${PROJECT_SOURCE_DIR}/scripts/testdata/make_hostile_commands.py)
execute_process(
  COMMAND ${Python3_EXECUTABLE} ${_hostile_generator} ${DQSKIN_HOSTILE_DIR}
  RESULT_VARIABLE _status OUTPUT_VARIABLE _output ERROR_VARIABLE _output)
if(NOT _status STREQUAL "0")
  message(FATAL_ERROR "scripts/testdata/make_hostile_commands.py failed (${_status}):\n${_output}")
endif()
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${_hostile_generator}
  ${PROJECT_SOURCE_DIR}/scripts/testdata/make_malformed.py ${PROJECT_SOURCE_DIR}/scripts/testdata/gltf_builder.py)

# dqskin_limit_test(NAME EXPECTED ARGS ... [TIMEOUT s] [options of dqskin_outcome_case])
# One case, limits.NAME: `dqskin ARGS` run in the generated folder under a 4 GiB address-space cap, with
# TIMEOUT seconds (default 60; DQSKIN_TIMEOUT_SCALE times that in the sanitizer build) for the command. Label "limits".
set(limits_scratch ${CMAKE_CURRENT_BINARY_DIR}/limits)
file(MAKE_DIRECTORY ${limits_scratch})
include(${CMAKE_CURRENT_LIST_DIR}/outcome_test.cmake)
function(dqskin_limit_test name expected)
  cmake_parse_arguments(T "" "TIMEOUT" "" ${ARGN})
  if(NOT DEFINED T_TIMEOUT)
    set(T_TIMEOUT 60)
  endif()
  math(EXPR T_TIMEOUT "${T_TIMEOUT} * ${DQSKIN_TIMEOUT_SCALE}")  # longer under the sanitizers (CMakeLists.txt)
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

# A clip of 2·10^5 s at 1 fps: 200,000 frames of figures. Past the ceiling the report's document was
# destroyed while the refusal unwound, and its destructor allocated (std::terminate: exit 134, two lines,
# a stray sheet). Now one line and nothing written.
dqskin_limit_test(report_long_clip_refused_in_one_line 2 FOLDER ${limits_scratch}/report_long_clip UNCHANGED
  ARGS report report/clip_2e5.gltf --fps 1 -o ${limits_scratch}/report_long_clip --max-memory 64M --quiet
  ONE_LINE TIMEOUT 120
  STDERR "^dqskin: report/clip_2e5.gltf: needs more memory than --max-memory 64.0 MiB allows \\(")

# A report is all of its files or none: SIGTERM while the sheet is written, and the leftovers of a
# SIGKILL removed by the next run (app/tests/report_signal.sh).
add_test(NAME limits.report_signal_all_or_nothing COMMAND bash ${PROJECT_SOURCE_DIR}/app/tests/report_signal.sh
  $<TARGET_FILE:dqskin_cli> ${DQSKIN_HOSTILE_DIR}/report/rig_300_joints.glb ${limits_scratch}/report_signal)
set_tests_properties(limits.report_signal_all_or_nothing PROPERTIES LABELS limits TIMEOUT 600
  PASS_REGULAR_EXPRESSION "PASS" FAIL_REGULAR_EXPRESSION "FAIL:")
if(DQSKIN_SANITIZE)  # llvmpipe's LLVM leaks (lib/CMakeLists.txt); report makes a GL context for its sheets
  set_tests_properties(limits.report_signal_all_or_nothing PROPERTIES ENVIRONMENT "LSAN_OPTIONS=detect_leaks=0")
endif()

# ---- diff --------------------------------------------------------------------------------------------------
# Images: read as float into memory the ceiling counts, after their declared size was checked against
# --max-memory. A valid 12000x2400 EXR at --max-memory 96M crashed (OpenImageIO's ImageBuf could not
# allocate it and the pixels were read through its null pointer); a 12000x1 one needed OpenImageIO's
# 66 MB read buffer; a 6 KB header declaring 12000x12000 is refused from the header.
dqskin_limit_test(diff_wide_exrs_within_16M 0 ARGS diff diff/wide_a.exr diff/wide_b.exr --max-memory 16M
  STDOUT "^PASS  diff/wide_a.exr  max 0 " STDERR "^$")
dqskin_limit_test(diff_exr_past_max_memory 2 ARGS diff diff/tall.exr diff/tall.exr --max-memory 96M ONE_LINE
  STDOUT "^FAIL  diff/tall.exr  cannot read diff/tall.exr: comparing it needs about 118 MiB "
  STDERR "^dqskin: diff/tall.exr: comparing it needs about 118 MiB \\(its 12000x2400 pixels of 1 channel as float\\), more than --max-memory 96.0 MiB\n$")
dqskin_limit_test(diff_exr_declaring_12000_squared 2 ARGS diff diff/declared_a.exr diff/declared_b.exr ONE_LINE
  MAX_RSS_MB 400 STDERR "^dqskin: diff/declared_a.exr: comparing it needs about 2.15 GiB \\(its 12000x12000 pixels of 4 channels as float\\), more than --max-memory 2.00 GiB\n$")
# Bake folders: an EXR texture declaring 12000x12000 was allocated at its declared size (2.7 GB at
# --max-memory 256M); a frame that is a symbolic link out of the folder was read and quoted; a parse
# error quoted the file (a PLY property's name, the JSON parser's "last read").
dqskin_limit_test(diff_bake_exr_declaring_12000_squared 2 ARGS diff diff/bake_exr/A diff/bake_exr/B --max-memory 256M
  ONE_LINE MAX_RSS_MB 400 STDOUT "^$"
  STDERR "^dqskin: diff/bake_exr/A/vat.exr: comparing it needs about 1.61 GiB \\(its 12000x12000 texels as positions\\), more than --max-memory 256 MiB\n$")
dqskin_limit_test(diff_bake_link_refused 2 ARGS diff diff/bake_link/A diff/bake_link/B ONE_LINE STDOUT "^$"
  STDERR "^dqskin: diff/bake_link/A/frame.ply: is a symbolic link, which diff does not follow in a bake folder\n$")
dqskin_limit_test(diff_bake_errors_quote_nothing 2 ARGS diff diff/bake_quote/A diff/bake_quote/B --json STDERR "^$"
  STDOUT "\"reason\": \"[^\"]*must be escaped to [^\"]*u0001\",\n.*\"reason\": \"PLY vertex property 1 is not float\",\n")
# glTF files: 22 million vertices declared by a 2.7 KB file (an accessor without a buffer) took all the
# memory there was, and a refusal of the memory ceiling named no file; 6 million fit as sides but not one
# frame of both. Errors of the pair name both files.
dqskin_limit_test(diff_vertices_declared 2 ARGS diff diff/vertices_a.gltf diff/vertices_b.gltf ONE_LINE MAX_RSS_MB 2000
  STDERR "^dqskin: diff/vertices_a.gltf: comparing its 22369620 vertices needs about 2.94 GiB, more than the [0-9.]+ [MG]iB that --max-memory 2.00 GiB leaves\n$")
dqskin_limit_test(diff_vertices_declared_under_ceiling 2 ARGS diff diff/vertices_a.gltf diff/vertices_b.gltf --max-memory 1500M
  ONE_LINE MAX_RSS_MB 1800 STDERR "^dqskin: diff/vertices_a.gltf: comparing its 22369620 vertices needs about 2.94 GiB, ")
dqskin_limit_test(diff_frame_past_max_memory 2 ARGS diff diff/vertices_6m_a.gltf diff/vertices_6m_b.gltf --backend cpu
  ONE_LINE MAX_RSS_MB 2200
  STDERR "^dqskin: diff/vertices_6m_a.gltf vs diff/vertices_6m_b.gltf: comparing a frame of their 12000000 vertices needs about ")
dqskin_limit_test(diff_no_clip_in_common_names_both 2 ARGS diff diff/quad.gltf diff/still.gltf ONE_LINE STDOUT "^$"
  STDERR "^dqskin: diff/quad.gltf vs diff/still.gltf: no clip in common: A has wave. B has no animations\n$")
dqskin_limit_test(diff_disjoint_meshes_name_both 2 ARGS diff diff/quad.gltf diff/apart.gltf ONE_LINE STDOUT "^$"
  STDERR "^dqskin: diff/quad.gltf vs diff/apart.gltf: the two files' meshes do not overlap at the rest pose ")
# SIGTERM while a folder diff writes heat maps: the image diff did not catch it, so it died without a word
# and a heat map being written could stay behind as a temporary. Now it stops as bake does.
add_test(NAME limits.diff_interrupted_writes_nothing_half
  COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/diff_interrupted.sh $<TARGET_FILE:dqskin_cli> ${limits_scratch}/diff/interrupted)
set_tests_properties(limits.diff_interrupted_writes_nothing_half PROPERTIES LABELS limits TIMEOUT 120)

# ---- lint ----------------------------------------------------------------------------------------------------
# A chain of 200,000 joints: lint walked from every joint up to its root and the skeleton (minutes); now
# about as long as loading the file (`dqskin info`: 2 s). --fix was as quadratic in the skeleton check;
# it reads the file four times (lint, the fix's data, the fixed .glb's JSON, lint of the fixed file):
# 7.5 s alone, 16 s beside two other tests on two cores, hence its 60 s.
file(MAKE_DIRECTORY ${limits_scratch}/lint)
# (Information only: its tip joint rests away from its bind pose, which its animated translation may reach.)
dqskin_limit_test(lint_200k_joint_chain 0 TIMEOUT 30
  ARGS lint lint/chain_200k.gltf --max-memory 1G MAX_RSS_MB 1024
  STDOUT "^lint/chain_200k.gltf: info\n  info    unused-joint \\(200000\\)")
dqskin_limit_test(lint_fix_200k_joint_chain 0 TIMEOUT 60
  ARGS lint --fix lint/chain_200k.gltf -o ${limits_scratch}/lint/chain_200k.fixed.glb --max-memory 1G MAX_RSS_MB 1024
  STDERR "^dqskin: lint: wrote [^\n]*/chain_200k.fixed.glb "
  STDOUT "\n[^\n]*chain_200k.fixed.glb: info\n  info    unused-joint \\(200000\\)")
# 1,000,000 vertices without weight and 50,000 joints: --fix compared each vertex with every joint for the
# nearest one (over a minute); a k-d tree answers each in about log(joints).
dqskin_limit_test(lint_fix_unweighted_vertices_50k_joints 0 TIMEOUT 30
  ARGS lint --fix lint/unweighted_50k.gltf -o ${limits_scratch}/lint/unweighted_50k.fixed.glb --max-memory 1G
  MAX_RSS_MB 1024 STDERR "^dqskin: lint: wrote [^\n]*/unweighted_50k.fixed.glb "
  STDOUT "\n[^\n]*unweighted_50k.fixed.glb: info\n")
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

# The morph animation holds every frame until its keys are chosen: past --max-memory it is refused while
# planning, before any other output of the bake (the vat texture here) is made, naming the frames,
# vertices and bytes, and what would fit.
dqskin_limit_test(bake_morph_past_max_memory_refused_before_work 2 FOLDER ${limits_scratch}/morph_refused UNCHANGED
  ARGS bake ${PROJECT_SOURCE_DIR}/testdata/twisted_cylinder.gltf --format vat,morph --fps 240 -o ${limits_scratch}/morph_refused
       --max-memory 2M --quiet
  ONE_LINE
  STDERR "^dqskin: [^ ]*/testdata/twisted_cylinder.gltf: clip twist: the morph animation holds every frame, 241 frames of 792 vertices in 4.37 MiB, more than --max-memory 2.00 MiB \\(fewer frames, with --fps or --frames, would fit\\)")
