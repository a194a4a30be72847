# `dqskin render` on the command line: help, file names, exit statuses and messages. Processes that make a
# GL context run with bake_test_environment (LeakSanitizer off under the sanitizers, see bake.cmake).
set(render_scratch ${CMAKE_CURRENT_BINARY_DIR}/render_cli)
set(render_rig ${PROJECT_SOURCE_DIR}/testdata/bending_arm.gltf)

include(${CMAKE_CURRENT_LIST_DIR}/cli_test.cmake)
function(dqskin_render_test name expected)
  dqskin_cli_test(cli.render_${name} ${expected} ${ARGN} ENVIRONMENT ${bake_test_environment} LABELS gpu)
  set_property(TEST cli.render_${name} APPEND PROPERTY FIXTURES_REQUIRED render_scratch)
endfunction()
# Every run starts from an empty scratch folder: images from an earlier build's shaders would otherwise be
# "existing files with different contents" to the tests that render without --force.
add_test(NAME cli.render_clean_scratch COMMAND sh -c "rm -rf '${render_scratch}' && mkdir -p '${render_scratch}/tmp'")
set_tests_properties(cli.render_clean_scratch PROPERTIES FIXTURES_SETUP render_scratch)

dqskin_render_test(help 0 ARGS render --help
  STDOUT "INPUT.*--out.*--anim.*--fps.*--frames.*--keys.*--times.*--mode.*--backend.*--shard.*--size.*--background.*--samples.*--shade.*--yaw.*--pitch.*--distance.*--fov.*--ortho.*--camera.*--format.*--sheet.*--sheet-cell.*--gif.*--quiet.*--json-progress.*Exit status")
# Names as bake gives them; the summary on stderr; --json-progress one line per frame, then a summary.
dqskin_render_test(writes_frames_named_like_bake 0 ARGS render ${render_rig} -o ${render_scratch}/frames --frames 0:2 --size 64x48
  STDERR "^rendered 3 frames of 1 input in [0-9.]+ s into [^\n]*/frames\ndeformed on (fast-cpu|gpu)[^\n]*, drawn by [^\n]+\n$")
dqskin_render_test(json_progress 0 ARGS render ${render_rig} -o ${render_scratch}/json --times 0,0.5 --size 32x32 --format exr --json-progress
  STDOUT "^{[^\n]*\"event\":\"progress\"[^\n]*\"frames_done\":1[^\n]*\"frames_per_s\":[^\n]*\n{[^\n]*\"eta_s\":0\.0,[^\n]*\"frames_done\":2[^\n]*\n{[^\n]*\"event\":\"summary\"[^\n]*\"files\":2")
dqskin_render_test(quiet_prints_nothing 0 ARGS render ${render_rig} -o ${render_scratch}/quiet --times 0 --size 32x32 --quiet
  STDOUT "^$" STDERR "^$")
dqskin_render_test(missing_input_exits_2 2 ARGS render ${render_scratch}/missing.gltf -o ${render_scratch}/missing
  STDERR "^dqskin: [^\n]*/missing.gltf: [^\n]+\n$")
dqskin_render_test(some_inputs_failed_exits_1 1 ARGS render ${render_scratch}/missing.gltf ${render_rig} -o ${render_scratch}/some --times 0 --size 32x32 --quiet
  STDERR "^dqskin: [^\n]*/missing.gltf: [^\n]+\n$")
# Without an input, the bundled rig into a temporary folder (under the scratch folder's TMPDIR here).
dqskin_cli_test(cli.render_default_input 0 ARGS render --times 0.5 --size 32x32
  ENVIRONMENT TMPDIR=${render_scratch}/tmp ${bake_test_environment} LABELS gpu
  STDERR "^dqskin: no input given: rendering the bundled textured_cylinder.gltf into [^\n]*/tmp/dqskin-render-[^\n]*/out\nrendered 1 frames of 1 input")
set_property(TEST cli.render_default_input APPEND PROPERTY FIXTURES_REQUIRED render_scratch)
dqskin_render_test(out_dir_required 2 ARGS render ${render_rig} STDERR "^dqskin: -o OUTDIR is required when inputs are given\n$")
dqskin_render_test(bad_size_exits_2 2 ARGS render ${render_rig} -o ${render_scratch}/x --size 64 STDERR "^dqskin: --size '64' is not WxH")
dqskin_render_test(bad_background_exits_2 2 ARGS render ${render_rig} -o ${render_scratch}/x --background red
  STDERR "^dqskin: --background 'red' is not")
dqskin_render_test(unknown_shade_exits_2 2 ARGS render ${render_rig} -o ${render_scratch}/x --shade toon
  STDERR "^dqskin: --shade 'toon' is not one of lit, normals, weights, mode-diff\n$")
dqskin_render_test(weights_need_a_joint 2 ARGS render ${render_rig} -o ${render_scratch}/x --shade weights
  STDERR "^dqskin: --shade weights needs --joint NAME\n$")
dqskin_render_test(unknown_joint_fails_the_input 2 ARGS render ${render_rig} -o ${render_scratch}/x --shade weights --joint nobody --times 0
  STDERR "^dqskin: [^\n]*bending_arm.gltf: --joint 'nobody': no node has that name\n$")
dqskin_render_test(mode_diff_prints_its_scale 0 ARGS render ${render_rig} -o ${render_scratch}/diff --shade mode-diff --frames 0:30:10 --size 32x32
  STDERR "^mode-diff [^\n]*bending_arm.gltf bend: red = [0-9.e-]+ \\(largest \\|lbs - dqs\\| position distance\\), dark blue = 0\n")
dqskin_render_test(unknown_format_exits_2 2 ARGS render ${render_rig} -o ${render_scratch}/x --format jpg
  STDERR "^dqskin: --format 'jpg' is not one of png, exr\n$")
dqskin_render_test(unknown_mode_exits_2 2 ARGS render ${render_rig} -o ${render_scratch}/x --mode slerp
  STDERR "^dqskin: --mode 'slerp' is not one of lbs, dqs, dib\n$")
dqskin_render_test(unknown_backend_exits_2 2 ARGS render ${render_rig} -o ${render_scratch}/x --backend vulkan
  STDERR "^dqskin: --backend 'vulkan' is not one of auto, egl, osmesa, fast-cpu, cpu\n$")
# dib has only the CPU reference; --backend cpu deforms there too. Both draw on the headless context.
dqskin_render_test(dib_renders 0 ARGS render ${render_rig} -o ${render_scratch}/dib --mode dib --times 0.5 --size 32x32 --quiet)
dqskin_render_test(cpu_backend_renders 0 ARGS render ${render_rig} -o ${render_scratch}/cpu --backend cpu --times 0.5 --size 32x32 --quiet)

# --camera: a glTF camera by node name, in its aspect ratio when no --size is given.
set(camera_rig ${PROJECT_SOURCE_DIR}/testdata/camera_dolly.gltf)
dqskin_render_test(camera_unknown_exits_2 2 ARGS render ${camera_rig} -o ${render_scratch}/x --camera nobody --times 0
  STDERR "^dqskin: [^\n]*camera_dolly.gltf: --camera 'nobody': no node of that name has a camera \\(camera nodes: 'dolly', 'top'\\)\n$")
dqskin_render_test(camera_on_a_file_without_cameras_exits_2 2 ARGS render ${render_rig} -o ${render_scratch}/x --camera dolly --times 0
  STDERR "--camera 'dolly': no node of that name has a camera \\(the file has none\\)\n$")
dqskin_render_test(camera_with_yaw_exits_2 2 ARGS render ${camera_rig} -o ${render_scratch}/x --camera dolly --yaw 10
  STDERR "^dqskin: --camera sets the view; it cannot be combined with --yaw, --pitch, --distance, --fov or --ortho\n$")
dqskin_render_test(camera_sets_the_size 0 ARGS render ${camera_rig} -o ${render_scratch}/camera --camera dolly --times 0 --quiet)
add_test(NAME cli.render_camera_size COMMAND ${CMAKE_COMMAND} -DPNG=${render_scratch}/camera/camera_dolly/bend/frame_0000.png
  -DWIDTH=768 -DHEIGHT=512 -P ${PROJECT_SOURCE_DIR}/app/tests/png_size.cmake)
set_tests_properties(cli.render_camera_size PROPERTIES LABELS gpu)
# A camera the loader finds invalid (znear 0) is a warning for a render that does not use it, and the
# input's error for one that does. The file is camera_dolly.gltf with that one value changed.
file(READ ${camera_rig} bad_camera_json)
string(JSON bad_camera_json SET "${bad_camera_json}" cameras 0 perspective znear 0)
set(bad_camera_rig ${CMAKE_CURRENT_BINARY_DIR}/bad_camera.gltf)
file(WRITE ${bad_camera_rig} "${bad_camera_json}")
dqskin_render_test(loader_warnings_are_printed 0 ARGS render ${bad_camera_rig} -o ${render_scratch}/bad_camera --times 0 --size 32x32
  STDERR "^dqskin: [^\n]*bad_camera.gltf: warning: camera 0: znear must be above 0. it cannot be rendered through\nrendered 1 frames")
dqskin_render_test(invalid_camera_fails_the_input 2 ARGS render ${bad_camera_rig} -o ${render_scratch}/bad_camera --camera dolly --times 0
  STDERR "^dqskin: [^\n]*bad_camera.gltf: camera 0: znear must be above 0. it cannot be rendered through\n$")
set_tests_properties(cli.render_camera_sets_the_size PROPERTIES FIXTURES_SETUP render_camera)
set_tests_properties(cli.render_camera_size PROPERTIES FIXTURES_REQUIRED render_camera)
dqskin_render_test(bad_shard_exits_2 2 ARGS render ${render_rig} -o ${render_scratch}/x --shard 2/2
  STDERR "^dqskin: --shard '2/2': I must be at least 0 and less than N\n$")
dqskin_render_test(no_gl_context_exits_3 3 ARGS render ${render_rig} -o ${render_scratch}/nogl --backend egl
  STDERR "^dqskin: no OpenGL 4.3 core context: ")
set_property(TEST cli.render_no_gl_context_exits_3 APPEND PROPERTY ENVIRONMENT
  "__EGL_VENDOR_LIBRARY_FILENAMES=${CMAKE_CURRENT_BINARY_DIR}/no-such-vendor.json")

# The files of a render, by name: frames 0..2 of the rig's only clip, and nothing else.
add_test(NAME cli.render_file_names COMMAND ${CMAKE_COMMAND} -DDIR=${render_scratch}/frames
  -P ${PROJECT_SOURCE_DIR}/app/tests/render_files.cmake)
set_tests_properties(cli.render_writes_frames_named_like_bake PROPERTIES FIXTURES_SETUP render_frames)
set_tests_properties(cli.render_file_names PROPERTIES FIXTURES_REQUIRED render_frames)

# --sheet and --gif: five frames of 64x48 in 32-pixel cells make a 3x2 grid (104x54 with the gaps) and a
# 64x48 GIF; a second run into the same folder (without --force) keeps every file, which it only does when
# the bytes are equal. With --shard the shard's own frames get files of their own.
dqskin_render_test(sheet_and_gif 0 ARGS render ${render_rig} -o ${render_scratch}/sheet --frames 0:4 --size 64x48
  --sheet --sheet-cell 32 --gif --force STDERR "^rendered 5 frames of 1 input in [0-9.]+ s into [^\n]*/sheet\ndeformed on [^\n]+\n$")
dqskin_render_test(sheet_and_gif_again 0 ARGS render ${render_rig} -o ${render_scratch}/sheet --frames 0:4 --size 64x48
  --sheet --sheet-cell 32 --gif --quiet)
add_test(NAME cli.render_sheet_files COMMAND ${CMAKE_COMMAND} -DDIR=${render_scratch}/sheet/bending_arm/bend
  -P ${PROJECT_SOURCE_DIR}/app/tests/render_sheet_files.cmake)
set_tests_properties(cli.render_sheet_and_gif PROPERTIES FIXTURES_SETUP render_sheet)
set_tests_properties(cli.render_sheet_and_gif_again cli.render_sheet_files PROPERTIES FIXTURES_REQUIRED render_sheet)
set_tests_properties(cli.render_sheet_files PROPERTIES DEPENDS cli.render_sheet_and_gif_again)
dqskin_render_test(bad_sheet_cell_exits_2 2 ARGS render ${render_rig} -o ${render_scratch}/x --sheet --sheet-cell 0
  STDERR "^dqskin: --sheet-cell 0: must be 1 to 4096 pixels\n$")
dqskin_render_test(sheet_of_a_shard 0 ARGS render ${render_rig} -o ${render_scratch}/sheet_shard --frames 0:4 --size 32x32
  --sheet --gif --shard 1/2 --force --quiet)
add_test(NAME cli.render_sheet_of_a_shard_files COMMAND ${CMAKE_COMMAND}
  -DFILES=${render_scratch}/sheet_shard/bending_arm/bend/sheet_shard1of2.png\;${render_scratch}/sheet_shard/bending_arm/bend/animation_shard1of2.gif
  -P ${PROJECT_SOURCE_DIR}/app/tests/render_sheet_files.cmake)
set_tests_properties(cli.render_sheet_of_a_shard PROPERTIES FIXTURES_SETUP render_sheet_shard)
set_tests_properties(cli.render_sheet_of_a_shard_files PROPERTIES FIXTURES_REQUIRED render_sheet_shard)
