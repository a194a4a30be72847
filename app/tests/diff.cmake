# `dqskin diff` on the command line: each case's exit status and report. The images are plain-text PPM
# (P3) written here at configure time, so no binary file is committed; OpenImageIO reads them as 8-bit RGB.
set(diff_scratch ${CMAKE_CURRENT_BINARY_DIR}/diff_cli)
file(REMOVE_RECURSE ${diff_scratch})

# A W×H PPM whose pixels are all `grey`, except the one at index `at` (-1: none), whose green is `green`.
function(dqskin_diff_ppm path width height grey at green)
  set(text "P3\n${width} ${height}\n255\n")
  math(EXPR last "${width} * ${height} - 1")
  foreach(i RANGE ${last})
    if(i EQUAL at)
      string(APPEND text "${grey} ${green} ${grey}\n")
    else()
      string(APPEND text "${grey} ${grey} ${grey}\n")
    endif()
  endforeach()
  file(WRITE ${path} "${text}")
endfunction()

set(d ${diff_scratch}/in)
dqskin_diff_ppm(${d}/a.ppm 2 2 128 -1 0)
dqskin_diff_ppm(${d}/same.ppm 2 2 128 -1 0)
dqskin_diff_ppm(${d}/slight.ppm 2 2 128 1 129)  # one step of 255 in one channel: 0.00392157
dqskin_diff_ppm(${d}/very.ppm 2 2 0 -1 0)       # 128/255 everywhere: 0.501961
dqskin_diff_ppm(${d}/wide.ppm 3 2 128 -1 0)
file(WRITE ${d}/bad.png "this is not a PNG file\n")
# Two folders: same.ppm equal, sub/slight.ppm a step apart, gone.ppm only in A, extra.ppm only in B; other
# files are ignored.
dqskin_diff_ppm(${d}/A/same.ppm 2 2 128 -1 0)
dqskin_diff_ppm(${d}/B/same.ppm 2 2 128 -1 0)
dqskin_diff_ppm(${d}/A/sub/slight.ppm 2 2 128 -1 0)
dqskin_diff_ppm(${d}/B/sub/slight.ppm 2 2 128 1 129)
dqskin_diff_ppm(${d}/A/gone.ppm 2 2 128 -1 0)
dqskin_diff_ppm(${d}/B/extra.ppm 2 2 128 -1 0)
file(WRITE ${d}/A/notes.txt "not an image\n")

include(${CMAKE_CURRENT_LIST_DIR}/cli_test.cmake)
function(dqskin_diff_test name expected)
  dqskin_cli_test(cli.diff_${name} ${expected} ${ARGN} )
endfunction()

set(pass_line "max 0  mean 0  RMS 0  PSNR inf dB  over warn 0 \\(0%\\)  over fail 0 \\(0%\\)")
set(slight_metrics "max 0.00392157 at \\(1, 0, G\\)  mean 0.000326797  RMS 0.00113206  PSNR 58.9226 dB")

dqskin_diff_test(help 0 ARGS diff --help
  STDOUT "A.*B.*--fail VAL=1e-06 .*--failpercent PERCENT=0 .*--hardfail VAL=inf .*--warn VAL=1e-06 .*--warnpercent PERCENT=0 .*--hardwarn VAL=inf .*--out.*--json.*--junit.*Exit status: 0 all pass, 1 warnings but no failure, 2 a failure")
# Two glTF files take bake's frame flags (--anim, --fps, --frames, --keys, --times), read as bake reads them,
# on A's clip; without them the key times of both files and the midpoints (bending_arm: 3 keys, 5 times).
set(diff_arm ${PROJECT_SOURCE_DIR}/testdata/bending_arm.gltf)
dqskin_diff_test(help_lists_the_frame_flags 0 ARGS diff --help STDOUT "--anim [^\n]*\n *--fps [^\n]*\n *--frames [^\n]*\n *--keys [^\n]*\n *--times ")
dqskin_diff_test(gltf_default_times 0 ARGS diff ${diff_arm} ${diff_arm} --backend cpu STDOUT "PASS  clip bend[^\n]*; 5 frames\n")
dqskin_diff_test(gltf_frames_as_bake 0 ARGS diff ${diff_arm} ${diff_arm} --backend cpu --frames 0:2 STDOUT "PASS  clip bend[^\n]*; 3 frames\n")
dqskin_diff_test(gltf_keys_of_a 0 ARGS diff ${diff_arm} ${diff_arm} --backend cpu --keys STDOUT "PASS  clip bend[^\n]*; 3 frames\n")
dqskin_diff_test(gltf_fps_grid 0 ARGS diff ${diff_arm} ${diff_arm} --backend cpu --fps 10 STDOUT "PASS  clip bend[^\n]*; 11 frames\n")
dqskin_diff_test(gltf_fps_and_times_exits_2 2 ARGS diff ${diff_arm} ${diff_arm} --fps 10 --times 0
  STDERR "^dqskin: give --fps or --times, not both\n$")
dqskin_diff_test(gltf_two_ways_exits_2 2 ARGS diff ${diff_arm} ${diff_arm} --keys --frames 0:1
  STDERR "^dqskin: --frames, --keys and --times choose frames in different ways; give one of them\n$")
dqskin_diff_test(identical_passes 0 ARGS diff ${d}/a.ppm ${d}/same.ppm
  STDOUT "^PASS  [^\n]*/a.ppm  ${pass_line}\nsummary: PASS \\(1 pair: 1 pass, 0 warn, 0 fail\\)\n$" STDERR "^$")
# idiff's defaults: a single 8-bit step is over --fail 1e-6.
dqskin_diff_test(slightly_different_fails_by_default 2 ARGS diff ${d}/a.ppm ${d}/slight.ppm
  STDOUT "^FAIL  [^\n]*/a.ppm  ${slight_metrics}  over warn 1 \\(25%\\)  over fail 1 \\(25%\\)\nsummary: FAIL \\(1 pair: 0 pass, 0 warn, 1 fail\\)\n$"
  STDERR "^$")
dqskin_diff_test(slightly_different_warns 1 ARGS diff ${d}/a.ppm ${d}/slight.ppm --fail 0.01 --warn 0.001
  STDOUT "^WARN  [^\n]*/a.ppm  ${slight_metrics}  over warn 1 \\(25%\\)  over fail 0 \\(0%\\)\nsummary: WARN \\(1 pair: 0 pass, 1 warn, 0 fail\\)\n$"
  STDERR "^$")
dqskin_diff_test(failpercent_lets_a_few_pixels_warn 1 ARGS diff ${d}/a.ppm ${d}/slight.ppm --failpercent 30
  STDOUT "^WARN  ")
dqskin_diff_test(very_different_fails 2 ARGS diff ${d}/a.ppm ${d}/very.ppm --fail 0.01 --warn 0.001 --out ${diff_scratch}/heat
  STDOUT "^FAIL  [^\n]*/a.ppm  max 0.501961 at \\(0, 0, R\\)  mean 0.501961  RMS 0.501961  PSNR 5.9866 dB  over warn 4 \\(100%\\)  over fail 4 \\(100%\\)  heat map [^\n]*/heat/a.ppm.diff.png\nsummary: FAIL \\(1 pair: 0 pass, 0 warn, 1 fail\\)\n$"
  STDERR "^$")
# The heat map is a complete image: equal to itself.
dqskin_diff_test(heat_map_is_an_image 0 ARGS diff ${diff_scratch}/heat/a.ppm.diff.png ${diff_scratch}/heat/a.ppm.diff.png
  STDOUT "^PASS  ")
set_tests_properties(cli.diff_very_different_fails PROPERTIES FIXTURES_SETUP diff_heat_map)
set_tests_properties(cli.diff_heat_map_is_an_image PROPERTIES FIXTURES_REQUIRED diff_heat_map)
dqskin_diff_test(size_mismatch_fails 2 ARGS diff ${d}/a.ppm ${d}/wide.ppm
  STDOUT "^FAIL  [^\n]*/a.ppm  size 2x2 vs 3x2\nsummary: FAIL \\(1 pair: 0 pass, 0 warn, 1 fail\\)\n$" STDERR "^$")
dqskin_diff_test(missing_file_fails 2 ARGS diff ${d}/a.ppm ${d}/none.ppm
  STDOUT "^FAIL  [^\n]*/a.ppm  cannot read [^\n]*/none.ppm: No such file or directory\nsummary: FAIL "
  STDERR "^dqskin: [^\n]*/none.ppm: No such file or directory\n$")
dqskin_diff_test(unreadable_file_fails 2 ARGS diff ${d}/a.ppm ${d}/bad.png
  STDOUT "^FAIL  [^\n]*/a.ppm  cannot read [^\n]*/bad.png: [^\n]+\nsummary: FAIL "
  STDERR "^dqskin: [^\n]*/bad.png: [^\n]+\n$")
# Folders: one line per relative path in byte order; missing and extra files fail.
dqskin_diff_test(folders_pair_by_relative_path 2 ARGS diff ${d}/A ${d}/B --fail 0.01 --warn 0.001
  STDOUT "^FAIL  extra.ppm  missing in A, only in B\nFAIL  gone.ppm  missing in B, only in A\nPASS  same.ppm  ${pass_line}\nWARN  sub/slight.ppm  ${slight_metrics}  over warn 1 \\(25%\\)  over fail 0 \\(0%\\)\nsummary: FAIL \\(4 pairs: 1 pass, 1 warn, 2 fail\\)\n$"
  STDERR "^$")
dqskin_diff_test(image_and_folder_compare_the_same_name 0 ARGS diff ${d}/A/same.ppm ${d}/B
  STDOUT "^PASS  [^\n]*/A/same.ppm  ")
dqskin_diff_test(json_is_one_document 2 ARGS diff ${d}/A ${d}/B --json
  STDOUT "^{\n  \"a\": \"[^\n]*/A\",\n  \"b\": \"[^\n]*/B\",\n  \"metric\": \"idiff\",\n  \"thresholds\": {\n    \"fail\": 1e-06,\n.*\"name\": \"sub/slight.ppm\",.*\"psnr\": 58.92[0-9]*,\n.*\"summary\": {\n    \"status\": \"FAIL\",\n    \"pairs\": 4,\n    \"pass\": 1,\n    \"warn\": 0,\n    \"fail\": 3\n  }\n}\n$"
  STDERR "^$")
dqskin_diff_test(junit_report_is_written 1 ARGS diff ${d}/a.ppm ${d}/slight.ppm --fail 0.01 --warn 0.001 --junit ${diff_scratch}/junit.xml
  STDOUT "^WARN  ")
add_test(NAME cli.diff_junit_report_content COMMAND ${CMAKE_COMMAND} -E cat ${diff_scratch}/junit.xml)
set_tests_properties(cli.diff_junit_report_content PROPERTIES
  PASS_REGULAR_EXPRESSION "^<\\?xml version=\"1.0\" encoding=\"UTF-8\"\\?>\n<testsuites name=\"dqskin diff\" tests=\"1\" failures=\"0\" errors=\"0\">\n.*<testcase classname=\"dqskin.diff\" name=\"[^\"]*/a.ppm\">\n      <system-out>WARN: 1 pixel \\(25%\\) over --warn 0.001, more than --warnpercent 0\n.*</testsuites>\n$"
  FIXTURES_REQUIRED diff_junit)
set_tests_properties(cli.diff_junit_report_is_written PROPERTIES FIXTURES_SETUP diff_junit)

# --metric flip: FLIP values judged by the thresholds given, and by none others; none given, any difference fails.
set(flip_number "[0-9.e-]+")
dqskin_diff_test(flip_identical_passes 0 ARGS diff ${d}/a.ppm ${d}/same.ppm --metric flip
  STDOUT "^PASS  [^\n]*/a.ppm  FLIP mean 0  weighted quartiles 0 0 0  max 0  over warn 0 \\(0%\\)  over fail 0 \\(0%\\)\nsummary: PASS " STDERR "^$")
dqskin_diff_test(flip_any_difference_fails_by_default 2 ARGS diff ${d}/a.ppm ${d}/slight.ppm --metric flip
  STDOUT "^FAIL  [^\n]*/a.ppm  FLIP mean ${flip_number}  weighted quartiles [^\n]* max ${flip_number} at \\(1, 0\\)  over warn 0 \\(0%\\)  over fail 0 \\(0%\\)\n" STDERR "^$")
dqskin_diff_test(flip_mean_under_failmean_passes 0 ARGS diff ${d}/a.ppm ${d}/slight.ppm --metric flip --failmean 0.2
  STDOUT "^PASS  ")
dqskin_diff_test(flip_max_over_hardwarn_warns 1 ARGS diff ${d}/a.ppm ${d}/slight.ppm --metric flip --failmean 0.2 --hardwarn 0.001
  STDOUT "^WARN  ")
dqskin_diff_test(flip_very_different_fails_with_a_heat_map 2 ARGS diff ${d}/a.ppm ${d}/very.ppm --metric flip --failmean 0.2
  --out ${diff_scratch}/flip_heat STDOUT "heat map [^\n]*/flip_heat/a.ppm.diff.png\n")
dqskin_diff_test(flip_viewing_conditions_give_ppd 2 ARGS diff ${d}/a.ppm ${d}/slight.ppm --metric flip --viewing 0.7 0.7 3840 --json
  STDOUT "\"metric\": \"flip\",\n  \"pixels_per_degree\": 67.0206432765822[0-9]*,\n")
dqskin_diff_test(flip_ppd_in_junit 2 ARGS diff ${d}/a.ppm ${d}/slight.ppm --metric flip --ppd 30 --junit ${diff_scratch}/flip.xml
  STDOUT "^FAIL  ")
dqskin_diff_test(metric_unknown_exits_2 2 ARGS diff ${d}/a.ppm ${d}/same.ppm --metric yee
  STDOUT "^$" STDERR "^dqskin: --metric 'yee' is not one of idiff, flip\n$")
dqskin_diff_test(flip_failpercent_needs_fail_exits_2 2 ARGS diff ${d}/a.ppm ${d}/same.ppm --metric flip --failpercent 1
  STDOUT "^$" STDERR "^dqskin: --failpercent needs --fail with --metric flip \\(the FLIP value it counts pixels over\\)\n$")
dqskin_diff_test(flip_ppd_out_of_range_exits_2 2 ARGS diff ${d}/a.ppm ${d}/same.ppm --metric flip --ppd 0.5
  STDOUT "^$" STDERR "^dqskin: --ppd must be from 1 to 1000 pixels per degree\n$")
dqskin_diff_test(flip_ppd_and_viewing_exits_2 2 ARGS diff ${d}/a.ppm ${d}/same.ppm --metric flip --ppd 40 --viewing 1 1 1000
  STDOUT "^$" STDERR "^dqskin: give --ppd or --viewing, not both\n$")
dqskin_diff_test(flip_viewing_needs_three_values_exits_2 2 ARGS diff ${d}/a.ppm ${d}/same.ppm --metric flip --viewing 1 1
  STDOUT "^$" STDERR "^dqskin: [^\n]*--viewing[^\n]*\n$")
dqskin_diff_test(ppd_without_flip_exits_2 2 ARGS diff ${d}/a.ppm ${d}/same.ppm --ppd 40
  STDOUT "^$" STDERR "^dqskin: --ppd and --viewing are FLIP's viewing conditions: give them with --metric flip\n$")
dqskin_diff_test(flip_on_gltf_exits_2 2 ARGS diff ${diff_arm} ${diff_arm} --metric flip
  STDOUT "^$" STDERR "^dqskin: --metric flip compares images. glTF files and bakes are compared by distance\n$")
dqskin_diff_test(negative_failmean_exits_2 2 ARGS diff ${d}/a.ppm ${d}/same.ppm --metric flip --failmean -0.1
  STDOUT "^$" STDERR "^dqskin: --failmean must be at least 0, not -0.1\n$")
add_test(NAME cli.diff_flip_junit_content COMMAND ${CMAKE_COMMAND} -E cat ${diff_scratch}/flip.xml)
set_tests_properties(cli.diff_flip_junit_content PROPERTIES
  PASS_REGULAR_EXPRESSION "<property name=\"metric\" value=\"flip\"/>\n.*<property name=\"failmean\" value=\"0\"/>\n.*<property name=\"pixels_per_degree\" value=\"30\"/>\n.*FLIP mean: "
  FIXTURES_REQUIRED diff_flip_junit)
set_tests_properties(cli.diff_flip_ppd_in_junit PROPERTIES FIXTURES_SETUP diff_flip_junit)

# --annotations: GitHub's workflow commands after the report and its step summary; GitLab's Code Quality report.
dqskin_diff_test(annotations_github_commands 1 ARGS diff ${d}/a.ppm ${d}/slight.ppm --fail 0.01 --warn 0.001
  --annotations github --annotations-file ${diff_scratch}/summary.md
  STDOUT "^WARN  [^\n]*\nsummary: WARN [^\n]*\n::warning file=[^\n]*/slight.ppm,title=dqskin diff%3A [^\n]*/a.ppm::1 pixel \\(25%25\\) over --warn 0.001, more than --warnpercent 0 \\(max 0.00392157, mean 0.000326797\\)\n$"
  STDERR "^$")
add_test(NAME cli.diff_annotations_github_summary COMMAND ${CMAKE_COMMAND} -E cat ${diff_scratch}/summary.md)
set_tests_properties(cli.diff_annotations_github_summary PROPERTIES
  PASS_REGULAR_EXPRESSION "^### dqskin diff [^\n]*/a.ppm [^\n]*/slight.ppm: WARN\n\n0 pass, 1 warn, 0 fail\n\n\\| \\| name \\| figures \\| reason \\|\n\\|---\\|---\\|---\\|---\\|\n\\| WARN \\| "
  FIXTURES_REQUIRED diff_summary)
set_tests_properties(cli.diff_annotations_github_commands PROPERTIES FIXTURES_SETUP diff_summary)
dqskin_diff_test(annotations_github_summary_from_environment 2 ARGS diff ${d}/a.ppm ${d}/very.ppm --annotations github
  ENVIRONMENT GITHUB_STEP_SUMMARY=${diff_scratch}/step_summary.md STDOUT "\n::error file=[^\n]*/very.ppm,")
add_test(NAME cli.diff_annotations_github_summary_environment_content COMMAND ${CMAKE_COMMAND} -E cat ${diff_scratch}/step_summary.md)
set_tests_properties(cli.diff_annotations_github_summary_environment_content PROPERTIES
  PASS_REGULAR_EXPRESSION "^### dqskin diff [^\n]*: FAIL\n" FIXTURES_REQUIRED diff_step_summary)
set_tests_properties(cli.diff_annotations_github_summary_from_environment PROPERTIES FIXTURES_SETUP diff_step_summary)
dqskin_diff_test(annotations_github_nothing_on_pass 0 ARGS diff ${diff_arm} ${diff_arm} --backend cpu --annotations github
  STDOUT "\nsummary: PASS [^\n]*\n$")
dqskin_diff_test(annotations_gitlab_report 2 ARGS diff ${d}/a.ppm ${d}/very.ppm --annotations gitlab
  --annotations-file ${diff_scratch}/codequality.json STDOUT "^FAIL  ")
add_test(NAME cli.diff_annotations_gitlab_content COMMAND ${CMAKE_COMMAND} -E cat ${diff_scratch}/codequality.json)
set_tests_properties(cli.diff_annotations_gitlab_content PROPERTIES
  PASS_REGULAR_EXPRESSION "^\\[\n  {\n    \"type\": \"issue\",\n    \"check_name\": \"dqskin-diff\",\n    \"description\": \"dqskin diff [^\n]*/a.ppm: FAIL, [^\n]*\",\n.*\"severity\": \"major\",\n    \"fingerprint\": \"[0-9a-f]+\",\n    \"location\": {\n      \"path\": \"[^\n]*/very.ppm\",\n      \"lines\": {\n        \"begin\": 1\n"
  FIXTURES_REQUIRED diff_codequality)
set_tests_properties(cli.diff_annotations_gitlab_report PROPERTIES FIXTURES_SETUP diff_codequality)
dqskin_diff_test(annotations_unknown_exits_2 2 ARGS diff ${d}/a.ppm ${d}/same.ppm --annotations jenkins
  STDOUT "^$" STDERR "^dqskin: --annotations 'jenkins' is not one of github, gitlab\n$")
dqskin_diff_test(annotations_github_with_json_exits_2 2 ARGS diff ${d}/a.ppm ${d}/same.ppm --annotations github --json
  STDOUT "^$" STDERR "^dqskin: --annotations github prints workflow commands after the report on stdout, [^\n]*\n$")
dqskin_diff_test(annotations_file_alone_exits_2 2 ARGS diff ${d}/a.ppm ${d}/same.ppm --annotations-file x.json
  STDOUT "^$" STDERR "^dqskin: --annotations-file needs --annotations github or gitlab\n$")
dqskin_diff_test(annotations_gitlab_unwritable_exits_2 2 ARGS diff ${d}/a.ppm ${d}/same.ppm --annotations gitlab
  --annotations-file /proc/dqskin-cannot-write-here/cq.json STDERR "^dqskin: /proc/dqskin-cannot-write-here/cq.json: [^\n]*\n$")

# --approve: fresh copies of the folders A and B for each run (the approval changes its goldens): a dry run
# lists sub/slight.ppm (differs) and extra.ppm (new); the approval makes them; gone.ppm has no candidate and
# keeps failing; the diff after it passes sub/slight.ppm. An approval that cannot be made (a file named sub
# where the new golden's folder would go) exits 2 with one line.
set(approve_dir ${diff_scratch}/approve)
add_test(NAME cli.diff_approve_setup COMMAND ${CMAKE_COMMAND} -E env sh -c
  "rm -rf '${approve_dir}' && mkdir -p '${approve_dir}/blocked' && cp -R '${d}/A' '${approve_dir}/golden' && cp -R '${d}/B' '${approve_dir}/out' && echo x > '${approve_dir}/blocked/sub'")
set_tests_properties(cli.diff_approve_setup PROPERTIES FIXTURES_SETUP diff_approve)
dqskin_diff_test(approve_dry_run 2 ARGS diff ${approve_dir}/golden ${approve_dir}/out --approve --dry-run
  STDOUT "\nsummary: FAIL [^\n]*\napproved: would add [^\n]*/golden/extra.ppm from [^\n]*/out/extra.ppm\napproved: would replace [^\n]*/golden/sub/slight.ppm with [^\n]*/out/sub/slight.ppm\napproved: 2 goldens would be replaced or added \\(dry run: nothing changed\\). then FAIL\n$")
dqskin_diff_test(approve_replaces 2 ARGS diff ${approve_dir}/golden ${approve_dir}/out --approve --json
  STDOUT "\"approval\": {\n    \"dry_run\": false,\n    \"files\": \\[\n      {\n        \"name\": \"extra.ppm\",")
dqskin_diff_test(approve_then_passes 2 ARGS diff ${approve_dir}/golden ${approve_dir}/out
  STDOUT "^PASS  extra.ppm  [^\n]*\nFAIL  gone.ppm  missing in B, only in A\nPASS  same.ppm  [^\n]*\nPASS  sub/slight.ppm  ")
dqskin_diff_test(approve_blocked_exits_2 2 ARGS diff ${approve_dir}/blocked ${d}/B --approve
  STDOUT "^$" STDERR "^dqskin: [^\n]*/blocked/sub[^\n]*\n$")
foreach(t approve_dry_run approve_replaces approve_then_passes approve_blocked_exits_2)
  set_tests_properties(cli.diff_${t} PROPERTIES FIXTURES_REQUIRED diff_approve)
endforeach()
set_tests_properties(cli.diff_approve_replaces PROPERTIES DEPENDS cli.diff_approve_dry_run)
set_tests_properties(cli.diff_approve_then_passes PROPERTIES DEPENDS cli.diff_approve_replaces)
dqskin_diff_test(dry_run_alone_exits_2 2 ARGS diff ${d}/a.ppm ${d}/same.ppm --dry-run
  STDOUT "^$" STDERR "^dqskin: --dry-run shows what --approve would do: give both\n$")
dqskin_diff_test(approve_gltf_exits_2 2 ARGS diff ${diff_arm} ${diff_arm} --approve
  STDOUT "^$" STDERR "^dqskin: --approve replaces golden images. [^\n]*\n$")

# Masks and presets: the one pixel that differs left out passes; a preset rule judges the pairs it matches.
dqskin_diff_ppm(${d}/mask_at_1.ppm 2 2 0 1 255)  # white at pixel 1 (green only: the first channel is 0)
dqskin_diff_ppm(${d}/mask_small.ppm 1 2 0 -1 0)
file(WRITE ${d}/preset.json "{\"rules\": [{\"match\": \"sub/*\", \"fail\": 0.01, \"warn\": 0.01}]}\n")
file(WRITE ${d}/bad_preset.json "{\"rules\": [{\"match\": \"*\", \"fial\": 1}]}\n")
dqskin_diff_test(ignore_rectangle_passes 0 ARGS diff ${d}/a.ppm ${d}/slight.ppm --ignore 1,0,1,1
  STDOUT "^PASS  [^\n]*  max 0  mean 0  RMS 0  PSNR inf dB  over warn 0 \\(0%\\)  over fail 0 \\(0%\\)  masked 1\n")
dqskin_diff_test(mask_first_channel_black_keeps_the_pixel 2 ARGS diff ${d}/a.ppm ${d}/slight.ppm --mask ${d}/mask_at_1.ppm
  STDOUT "^FAIL  ")
dqskin_diff_test(preset_rule_judges_its_pairs 2 ARGS diff ${d}/A ${d}/B --preset ${d}/preset.json
  STDOUT "\nPASS  sub/slight.ppm  [^\n]*  rule sub/\\*\n")
dqskin_diff_test(preset_unknown_key_exits_2 2 ARGS diff ${d}/A ${d}/B --preset ${d}/bad_preset.json
  STDOUT "^$" STDERR "^dqskin: [^\n]*/bad_preset.json: rules\\[0\\]: unknown key \"fial\"\n$")
dqskin_diff_test(preset_missing_exits_2 2 ARGS diff ${d}/A ${d}/B --preset ${d}/no_preset.json
  STDOUT "^$" STDERR "^dqskin: [^\n]*/no_preset.json: cannot read the preset file\n$")
dqskin_diff_test(mask_of_another_size_exits_2 2 ARGS diff ${d}/a.ppm ${d}/slight.ppm --mask ${d}/mask_small.ppm
  STDOUT "^$" STDERR "^dqskin: [^\n]*/mask_small.ppm: the mask is 1x2, the images 2x2\n$")
dqskin_diff_test(ignore_malformed_exits_2 2 ARGS diff ${d}/a.ppm ${d}/slight.ppm --ignore 1,0,0,1
  STDOUT "^$" STDERR "^dqskin: --ignore '1,0,0,1' is not X,Y,WIDTH,HEIGHT in pixels [^\n]*\n$")
dqskin_diff_test(mask_on_gltf_exits_2 2 ARGS diff ${diff_arm} ${diff_arm} --ignore 0,0,1,1
  STDOUT "^$" STDERR "^dqskin: --mask, --ignore and --preset apply to images. [^\n]*\n$")

# --html: the page of a folder diff (missing, passing and warning pairs) and of a FLIP diff in headless
# Chromium (lib/diff/diff_page_check.mjs): every pair a section in order, every picture decoded, nothing
# from the network, the toggle and the swipe working. Skipped with a printed reason without Node.js or
# Chromium.
foreach(page_case idiff flip)
  set(page_args --fail\;0.01\;--warn\;0.001)
  if(page_case STREQUAL flip)
    set(page_args --metric\;flip\;--failmean\;0.5)
  endif()
  add_test(NAME cli.diff_html_page_${page_case}
           COMMAND ${CMAKE_COMMAND} -DDQSKIN=$<TARGET_FILE:dqskin_cli> -DNODE=${DQSKIN_NODE} -DCHROMIUM=${DQSKIN_CHROMIUM}
                   -DSCRIPT=${PROJECT_SOURCE_DIR}/lib/diff/diff_page_check.mjs -DA=${d}/A -DB=${d}/B
                   "-DARGS=${page_args}" -DWORK=${diff_scratch}/html_${page_case}
                   -P ${PROJECT_SOURCE_DIR}/lib/diff/diff_page_check.cmake)
  set_tests_properties(cli.diff_html_page_${page_case} PROPERTIES SKIP_REGULAR_EXPRESSION "diff_page_check: SKIPPED" TIMEOUT 120)
endforeach()
dqskin_diff_test(html_into_a_folder_of_other_files_exits_2 2 ARGS diff ${d}/a.ppm ${d}/same.ppm --html ${d}/A
  STDOUT "^$" STDERR "^dqskin: [^\n]*/A: --html replaces its folder, and this one holds other files than a dqskin diff page. [^\n]*\n$")
dqskin_diff_test(html_with_a_trailing_slash 1 ARGS diff ${d}/a.ppm ${d}/slight.ppm --fail 0.01 --warn 0.001
  --html ${diff_scratch}/slash_page/ STDOUT "^WARN  ")
dqskin_diff_test(html_dot_exits_2 2 ARGS diff ${d}/a.ppm ${d}/same.ppm --html .
  STDOUT "^$" STDERR "^dqskin: --html '.': give the page a folder of its own \\(not '.', '..' or '/'\\)\n$")
dqskin_diff_test(out_inside_html_exits_2 2 ARGS diff ${d}/a.ppm ${d}/very.ppm --html ${diff_scratch}/outpage
  --out ${diff_scratch}/outpage/heat STDOUT "^$" STDERR "^dqskin: --out [^\n]* is inside --html [^\n]*, which the page replaces: [^\n]*\n$")
dqskin_diff_test(gltf_out_inside_html_exits_2 2 ARGS diff ${diff_arm} ${diff_arm} --html ${diff_scratch}/gltf_outpage
  --out ${diff_scratch}/gltf_outpage/heat STDOUT "^$" STDERR "^dqskin: --out [^\n]* is inside --html [^\n]*, which the page replaces: [^\n]*\n$")
# The page of two glTF files, B with one key of the elbow turned (make_diff_cases.py): the clip's section,
# both pictures, the chart with a point per frame, the toggle and the swipe. Renders through a GL context:
# Mesa's leaks are not ours (app/CMakeLists.txt).
find_package(Python3 COMPONENTS Interpreter REQUIRED)
set(page_args --relative\;--fail\;1e-3\;--warn\;1e-4\;--image-size\;256)
set(page_make rotate-key\;--joint\;elbow)
add_test(NAME cli.diff_html_page_gltf
         COMMAND ${CMAKE_COMMAND} -DDQSKIN=$<TARGET_FILE:dqskin_cli> -DNODE=${DQSKIN_NODE} -DCHROMIUM=${DQSKIN_CHROMIUM}
                 -DSCRIPT=${PROJECT_SOURCE_DIR}/lib/diff/diff_page_check.mjs -DA=${diff_arm}
                 -DB=${diff_scratch}/html_gltf/b.gltf -DPYTHON=${Python3_EXECUTABLE}
                 -DMAKE_SCRIPT=${PROJECT_SOURCE_DIR}/scripts/testdata/make_diff_cases.py "-DMAKE=${page_make}"
                 "-DARGS=${page_args}" -DWORK=${diff_scratch}/html_gltf
                 -P ${PROJECT_SOURCE_DIR}/lib/diff/diff_page_check.cmake)
set_tests_properties(cli.diff_html_page_gltf PROPERTIES SKIP_REGULAR_EXPRESSION "diff_page_check: SKIPPED" TIMEOUT 120
                     ENVIRONMENT "${bake_test_environment}" LABELS gpu)

# Usage and input errors: one line, exit status 2, no report.
dqskin_diff_test(negative_threshold_exits_2 2 ARGS diff ${d}/a.ppm ${d}/same.ppm --fail -1
  STDOUT "^$" STDERR "^dqskin: --fail must be at least 0, not -1\n$")
dqskin_diff_test(percent_over_100_exits_2 2 ARGS diff ${d}/a.ppm ${d}/same.ppm --warnpercent 150
  STDOUT "^$" STDERR "^dqskin: --warnpercent must be from 0 to 100, not 150\n$")
dqskin_diff_test(folder_against_image_exits_2 2 ARGS diff ${d}/A ${d}/a.ppm
  STDOUT "^$" STDERR "^dqskin: [^\n]*/a.ppm: not a folder, but A \\([^\n]*/A\\) is one. give two images or two folders\n$")
dqskin_diff_test(folder_against_nothing_exits_2 2 ARGS diff ${d}/A ${d}/no-such-folder
  STDOUT "^$" STDERR "^dqskin: [^\n]*/no-such-folder: no such folder \\(A, [^\n]*/A, is a folder\\)\n$")
dqskin_diff_test(one_argument_exits_2 2 ARGS diff ${d}/a.ppm
  STDOUT "^$" STDERR "^dqskin: B is required \\(see dqskin --help\\)\n$")
dqskin_diff_test(unwritable_junit_exits_2 2 ARGS diff ${d}/a.ppm ${d}/same.ppm --junit /proc/dqskin-cannot-write-here/report.xml
  STDERR "^dqskin: /proc/dqskin-cannot-write-here/report.xml: [^\n]*\n$")
