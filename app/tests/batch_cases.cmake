# Files people have, in batches (scripts/testdata/make_batch_cases.py): a glTF file is known by its bytes in every
# command, whatever its name (a .vrm avatar, a .glb without extension, a .gltf named .dat); a batch goes on
# past a file without a skin, a file without animations under --anim 0, and clips shorter than --frames B.
find_package(Python3 COMPONENTS Interpreter REQUIRED)
set(DQSKIN_BATCH_DIR ${CMAKE_CURRENT_BINARY_DIR}/batch_cases)
set(_batch_generator ${PROJECT_SOURCE_DIR}/scripts/testdata/make_batch_cases.py)
execute_process(
  COMMAND ${Python3_EXECUTABLE} ${_batch_generator} ${DQSKIN_BATCH_DIR} ${PROJECT_SOURCE_DIR}/testdata/bending_arm.gltf
  RESULT_VARIABLE _status OUTPUT_VARIABLE _output ERROR_VARIABLE _output)
if(NOT _status STREQUAL "0")
  message(FATAL_ERROR "scripts/testdata/make_batch_cases.py failed (${_status}):\n${_output}")
endif()
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${_batch_generator}
  ${PROJECT_SOURCE_DIR}/scripts/testdata/gltf_builder.py ${PROJECT_SOURCE_DIR}/testdata/bending_arm.gltf)

set(batch_scratch ${CMAKE_CURRENT_BINARY_DIR}/batch_out)
include(${CMAKE_CURRENT_LIST_DIR}/outcome_test.cmake)
# dqskin_batch_test(NAME EXPECTED [GPU] ARGS ... [options of dqskin_outcome_case]): batch.NAME, run in the
# generated folder; GPU for the commands that make a GL context (render, report).
function(dqskin_batch_test name expected)
  cmake_parse_arguments(T "GPU" "" "" ${ARGN})
  set(label batch)
  if(T_GPU)
    set(label gpu)
  endif()
  dqskin_outcome_case(batch.${name} ${expected} WORKING_DIRECTORY ${DQSKIN_BATCH_DIR} LABEL ${label} TIMEOUT 120
    CTEST_TIMEOUT 180 ${T_UNPARSED_ARGUMENTS})
endfunction()

# ---- A glTF file under any name -------------------------------------------------------------------------
# A .vrm is a GLB: every command reads it as one. diff chose by the name and read it as an image.
dqskin_batch_test(vrm_info 0 ARGS info rig.vrm
  STDOUT "skinned meshes: 1\n.*animations: 1\n.*extension VRMC_vrm is used but not supported")
dqskin_batch_test(vrm_lint 0 ARGS lint rig.vrm STDOUT "^rig.vrm: clean\n")
dqskin_batch_test(vrm_bake 0 ARGS bake rig.vrm -o ${batch_scratch}/vrm_bake --frames 0:2 --format glb,ply --quiet
  FOLDER ${batch_scratch}/vrm_bake PRESENT ${batch_scratch}/vrm_bake/rig/bend/frame_0002.ply)
dqskin_batch_test(vrm_render 0 GPU ARGS render rig.vrm -o ${batch_scratch}/vrm_render --frames 0:0 --size 32x32 --quiet
  FOLDER ${batch_scratch}/vrm_render PRESENT ${batch_scratch}/vrm_render/rig/bend/frame_0000.png)
dqskin_batch_test(vrm_report 0 GPU ARGS report rig.vrm -o ${batch_scratch}/vrm_report --frames 0:2 --image-size 32 --quiet
  FOLDER ${batch_scratch}/vrm_report PRESENT ${batch_scratch}/vrm_report/rig/report.json)
# Two VRM files of one geometry (their metadata differ): diff compares the deformed surfaces and passes.
dqskin_batch_test(vrm_diff_compares_geometry 0 ARGS diff rig.vrm rig_b.vrm --fps 10
  STDOUT "\nPASS  clip bend, .*summary: PASS \\(1 clips: 1 pass")
# A GLB without an extension against the same rig as a .gltf named .dat.
dqskin_batch_test(unnamed_glb_diff_compares_geometry 0 ARGS diff rig_glb_no_extension rig_gltf.dat --fps 10
  STDOUT "\nPASS  clip bend, .*summary: PASS \\(1 clips: 1 pass")
# A glTF file against an image is still refused in one line.
dqskin_batch_test(vrm_against_text_refused 2 ARGS diff rig.vrm done.txt ONE_LINE
  STDERR "^dqskin: compare two glTF files \\(.gltf, .glb, .vrm\\) or two images or folders of images, not one of each\n$")

# ---- A batch goes on ------------------------------------------------------------------------------------
# No skin: report says there is nothing to report for it and reports the others (it failed the batch).
dqskin_batch_test(report_goes_on_past_a_file_without_skin 0 GPU
  ARGS report no_skin.gltf rig.vrm -o ${batch_scratch}/report_no_skin --frames 0:2 --image-size 32
  STDERR "^dqskin: no_skin.gltf: warning: no skinned mesh in the scene: nothing to report. no report is written for it\n"
  FOLDER ${batch_scratch}/report_no_skin PRESENT ${batch_scratch}/report_no_skin/rig/report.json
  ABSENT ${batch_scratch}/report_no_skin/no_skin)
# --format bones on a file without skins says so, and bakes the other formats (it said nothing).
dqskin_batch_test(bones_of_a_file_without_skin_noted 0 ARGS bake no_skin.gltf -o ${batch_scratch}/bones_no_skin
  --format glb,bones --frames 0:1
  STDERR "^dqskin: no_skin.gltf: warning: the scene has no skinned mesh, so --format bones writes no bone texture for it\n"
  FOLDER ${batch_scratch}/bones_no_skin PRESENT ${batch_scratch}/bones_no_skin/no_skin/bend/frame_0001.glb)
# --anim 0 on a file without animations: its rest pose, in bake, render and report (all three refused it).
set(_rest_pose_warning "^dqskin: no_clips.gltf: warning: the file has no animations. --anim 0 takes its rest pose\n")
dqskin_batch_test(bake_anim_0_without_clips_is_the_rest_pose 0 ARGS bake no_clips.gltf --anim 0 -o ${batch_scratch}/anim0_bake
  STDERR "${_rest_pose_warning}" FOLDER ${batch_scratch}/anim0_bake PRESENT ${batch_scratch}/anim0_bake/no_clips/rest/frame_0000.glb)
dqskin_batch_test(render_anim_0_without_clips_is_the_rest_pose 0 GPU ARGS render no_clips.gltf --anim 0 --size 32x32
  -o ${batch_scratch}/anim0_render
  STDERR "${_rest_pose_warning}" FOLDER ${batch_scratch}/anim0_render PRESENT ${batch_scratch}/anim0_render/no_clips/rest/frame_0000.png)
dqskin_batch_test(report_anim_0_without_clips_is_the_rest_pose 0 GPU ARGS report no_clips.gltf --anim 0 --image-size 32
  -o ${batch_scratch}/anim0_report
  STDERR "${_rest_pose_warning}" FOLDER ${batch_scratch}/anim0_report PRESENT ${batch_scratch}/anim0_report/no_clips/report.json)
# --frames past the end of the 0.4 s clip (frames 0..12 at 30 fps): it gives the frames it has, with a
# warning; the 2 s clip gives all that were asked for (one short clip failed the whole batch).
set(_short_clip "animation 'short' \\(0.4 s\\) has frames 0..12 at 30 fps")
dqskin_batch_test(frames_past_a_short_clip 0 ARGS bake two_lengths.gltf --frames 0:59 --format ply -o ${batch_scratch}/past_short
  STDERR "^dqskin: two_lengths.gltf: warning: ${_short_clip}, so --frames 0:59 gives its frames 0..12\n"
  FOLDER ${batch_scratch}/past_short
  PRESENT ${batch_scratch}/past_short/two_lengths/short/frame_0012.ply ${batch_scratch}/past_short/two_lengths/long/frame_0059.ply
  ABSENT ${batch_scratch}/past_short/two_lengths/short/frame_0013.ply)
# A range that starts past the short clip's end leaves it out.
dqskin_batch_test(frames_after_a_short_clip 0 ARGS bake two_lengths.gltf --frames 20:40:10 --format ply -o ${batch_scratch}/after_short
  STDERR "^dqskin: two_lengths.gltf: warning: ${_short_clip}: --frames 20:40:10 asks for none of them. it is left out\n"
  FOLDER ${batch_scratch}/after_short
  PRESENT ${batch_scratch}/after_short/two_lengths/long/frame_0020.ply ${batch_scratch}/after_short/two_lengths/long/frame_0040.ply
  ABSENT ${batch_scratch}/after_short/two_lengths/short)
# Past the end of every clip: one line naming the longest, nothing written.
dqskin_batch_test(frames_past_every_clip 2 ARGS bake two_lengths.gltf --frames 70:80 -o ${batch_scratch}/past_all ONE_LINE
  STDERR "^dqskin: two_lengths.gltf: --frames 70:80 asks for frames past the end of every animation. the longest, animation 'long' \\(2 s\\) has frames 0..60 at 30 fps\n$"
  FOLDER ${batch_scratch}/past_all UNCHANGED)
# render and report take --frames the same way.
dqskin_batch_test(render_frames_past_a_short_clip 0 GPU ARGS render two_lengths.gltf --frames 10:14:2 --size 16x16
  -o ${batch_scratch}/render_past_short
  STDERR "^dqskin: two_lengths.gltf: warning: ${_short_clip}, so --frames 10:14:2 gives its frames 10..12\n"
  FOLDER ${batch_scratch}/render_past_short
  PRESENT ${batch_scratch}/render_past_short/two_lengths/short/frame_0012.png ${batch_scratch}/render_past_short/two_lengths/long/frame_0014.png
  ABSENT ${batch_scratch}/render_past_short/two_lengths/short/frame_0014.png)
dqskin_batch_test(report_frames_past_a_short_clip 0 GPU ARGS report two_lengths.gltf --frames 10:14 --image-size 32
  -o ${batch_scratch}/report_past_short
  STDERR "^dqskin: two_lengths.gltf: warning: ${_short_clip}, so --frames 10:14 gives its frames 10..12\n"
  FOLDER ${batch_scratch}/report_past_short PRESENT ${batch_scratch}/report_past_short/two_lengths/report.json)
