# `dqskin bake --sockets / --root-motion` on the command line: the refusals (one line naming the file and
# the problem, exit 2, nothing written for that input) and the files a good run adds. The numbers (the prop
# placed by the socket transforms, in place plus the track giving back the original) are checked by
# dqskin_bake_tests (lib/bake/motion_files_test.cpp).
set(motion_scratch ${CMAKE_CURRENT_BINARY_DIR}/motion_cli)
set(socket_rig ${PROJECT_SOURCE_DIR}/testdata/socket_prop.gltf)
add_test(NAME cli.motion_clean_scratch COMMAND sh -c "rm -rf '${motion_scratch}' && mkdir -p '${motion_scratch}'")
set_tests_properties(cli.motion_clean_scratch PROPERTIES FIXTURES_SETUP motion_scratch)

# A refused input: exit 2, one line "dqskin: FILE: MESSAGE", and its output folder never appears.
function(dqskin_motion_refusal name stderr)
  set(args "bake;${socket_rig};-o;${motion_scratch}/${name};--format;ply;--backend;fast-cpu;${ARGN}")
  add_test(NAME cli.motion_${name} COMMAND ${CMAKE_COMMAND} -DCOMMAND=$<TARGET_FILE:dqskin_cli> "-DARGS=${args}"
    -DEXPECTED=2 "-DSTDERR_REGEX=^dqskin: [^\n]*/socket_prop.gltf: ${stderr}\n$" -DONE_LINE=ON
    -DFOLDER=${motion_scratch}/${name} -DUNCHANGED=ON -P ${PROJECT_SOURCE_DIR}/app/tests/expect_outcome.cmake)
  set_tests_properties(cli.motion_${name} PROPERTIES FIXTURES_REQUIRED motion_scratch)
endfunction()
dqskin_motion_refusal(unknown_socket_exits_2 "--sockets: no node is named 'Hand'" --sockets hand,Hand)
dqskin_motion_refusal(socket_index_out_of_range_exits_2 "--sockets: there is no node #9 \\(the file has 4 nodes\\)"
  --sockets "#9")
dqskin_motion_refusal(unknown_root_exits_2 "--root-joint: no node is named 'hips'" --root-motion in-place --root-joint hips)
dqskin_motion_refusal(root_not_an_ancestor_exits_2
  "--root-joint: the root 'hand' \\(#2\\) is not an ancestor of joint 'body' \\(#1\\) of skin 0, so its motion is not the skin's"
  --root-motion in-place --root-joint hand)
dqskin_motion_refusal(prop_as_root_exits_2 "--root-joint: the root 'sword' \\(#3\\) is not an ancestor of joint 'body' \\(#1\\)[^\n]*"
  --root-motion in-place --root-joint "#3")

include(${CMAKE_CURRENT_LIST_DIR}/cli_test.cmake)
dqskin_cli_test(cli.motion_unknown_root_motion_exits_2 2 ARGS bake ${socket_rig} -o ${motion_scratch}/x --root-motion slide
  STDERR "^dqskin: --root-motion 'slide' is not one of none, in-place\n$")
dqskin_cli_test(cli.motion_root_joint_alone_exits_2 2 ARGS bake ${socket_rig} -o ${motion_scratch}/x --root-joint body
  STDERR "^dqskin: --root-joint is for --root-motion in-place\n$")
# A good run lists the files (a dry run writes nothing), and then writes them.
dqskin_cli_test(cli.motion_dry_run_lists_the_files 0 ARGS bake ${socket_rig} -o ${motion_scratch}/dry --dry-run
  --format ply --sockets hand --root-motion in-place
  STDOUT "socket_prop/walk/frame_0060.ply\n[^\n]*socket_prop/walk/root_motion.json\n[^\n]*socket_prop/walk/sockets.exr\n[^\n]*socket_prop/walk/sockets.json\n$")
dqskin_cli_test(cli.motion_writes_the_files 0 ARGS bake ${socket_rig} -o ${motion_scratch}/good --quiet --format glb --backend fast-cpu
  --sockets "hand,#3" --root-motion in-place --root-joint body)
set_tests_properties(cli.motion_dry_run_lists_the_files cli.motion_writes_the_files PROPERTIES FIXTURES_REQUIRED motion_scratch)
add_test(NAME cli.motion_files_in_the_manifest COMMAND sh -c
  "grep -q '\"socket_prop/walk/sockets.exr\"' '${motion_scratch}/good/manifest.json' && grep -q '\"socket_prop/walk/root_motion.json\"' '${motion_scratch}/good/manifest.json' && grep -q '\"name\": \"sword\"' '${motion_scratch}/good/socket_prop/walk/sockets.json'")
set_tests_properties(cli.motion_files_in_the_manifest PROPERTIES DEPENDS cli.motion_writes_the_files FIXTURES_REQUIRED motion_scratch)
# With --combine-clips and only textures, no other output makes the animations' folders: the motion files
# make them.
dqskin_cli_test(cli.motion_with_combined_clips 0 ARGS bake ${socket_rig} -o ${motion_scratch}/combined --quiet --format vat
  --combine-clips --sockets hand --root-motion in-place --backend fast-cpu)
set_tests_properties(cli.motion_with_combined_clips PROPERTIES FIXTURES_REQUIRED motion_scratch)
add_test(NAME cli.motion_with_combined_clips_files COMMAND sh -c
  "test -s '${motion_scratch}/combined/socket_prop/walk/sockets.exr' && test -s '${motion_scratch}/combined/socket_prop/walk/root_motion.json'")
set_tests_properties(cli.motion_with_combined_clips_files PROPERTIES DEPENDS cli.motion_with_combined_clips
  FIXTURES_REQUIRED motion_scratch)
