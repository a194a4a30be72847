# The command line against hostile inputs (docs/SECURITY.md): what each of bake, render, diff and info does
# with files made to read outside their folder, to leave outputs behind, to hang, to print terminal escapes
# or to overflow; each test failed on the code before the hardening. Inputs are make_malformed.py's jobs/.
set(hostile ${DQSKIN_MALFORMED_DIR}/jobs)
set(hard_scratch ${CMAKE_CURRENT_BINARY_DIR}/hardening)
file(MAKE_DIRECTORY ${hard_scratch})
set(rig ${PROJECT_SOURCE_DIR}/testdata/bending_arm.gltf)

# dqskin_outcome_test(NAME EXPECTED ARGS ... [STDERR regex] [FOLDER dir] [more options of dqskin_outcome_case])
include(${CMAKE_CURRENT_LIST_DIR}/outcome_test.cmake)
function(dqskin_outcome_test name expected)
  dqskin_outcome_case(cli.hardening_${name} ${expected} WORKING_DIRECTORY ${hostile} LABEL hardening
    CTEST_TIMEOUT 120 ${ARGN})
endfunction()

# ---- The resource root: a sibling folder only with --resource-root ----------------------------------------
# An image outside the root is not read: the file loads with a warning (the renderer has no texture).
dqskin_outcome_test(image_in_sibling_folder_not_read 0 ARGS info models/shared_texture.gltf STDERR "^$"
  STDOUT "\n    image 0 uri '../textures/checker.png' leads outside the model's folder \\(to [^\n]*\\). dqskin does not read it. textures using it are not drawn\n")
dqskin_outcome_test(resource_root_widens_the_folder 0 ARGS info models/shared_texture.gltf --resource-root textures
  STDERR "^$")
dqskin_outcome_test(resource_root_reaches_the_glb_writer 0 FOLDER ${hard_scratch}/root_bake
  ARGS bake models/shared_texture.gltf -o ${hard_scratch}/root_bake --resource-root textures --frames 0:0 --quiet
  PRESENT ${hard_scratch}/root_bake/shared_texture/wave/frame_0000.glb)
dqskin_outcome_test(resource_root_reaches_the_renderer 0 FOLDER ${hard_scratch}/root_render
  ARGS render models/shared_texture.gltf -o ${hard_scratch}/root_render --resource-root textures --frames 0:0
       --size 32x32 --quiet
  PRESENT ${hard_scratch}/root_render/shared_texture/wave/frame_0000.png)
# The landed code embedded /etc/passwd in every baked glb of such a file; now the image is not read (a
# warning) and the glb holds none of its bytes.
# On failure it says which check failed and shows what dqskin printed.
set(out ${hard_scratch}/traversal)
add_test(NAME cli.hardening_image_outside_the_root_is_not_embedded COMMAND sh -c
  "rm -rf '${out}' && '$<TARGET_FILE:dqskin_cli>' bake '${hostile}/image_traversal.gltf' -o '${out}' --frames 0:0 2>'${out}.err'; s=$?; cat '${out}.err'; \
   [ $s = 0 ] || { echo \"FAILED: exit status $s\"; exit 1; }; \
   grep -q \"image 0 uri '../../../../../../../../etc/passwd' leads outside\" '${out}.err' || { echo 'FAILED: no warning'; exit 1; }; \
   if grep -rl 'root:' '${out}'; then echo 'FAILED: bytes of /etc/passwd in these files'; exit 1; fi")
set_tests_properties(cli.hardening_image_outside_the_root_is_not_embedded PROPERTIES LABELS hardening
  ENVIRONMENT "${bake_test_environment}")
dqskin_outcome_test(resource_root_must_be_a_folder 2 ARGS info models/shared_texture.gltf --resource-root good.png
  ONE_LINE STDERR "^dqskin: --resource-root good.png: not a folder\n$")

# ---- A failed input leaves the output folder as it was -----------------------------------------------------
# 70,000 joints: a bone texture wider than any GPU's, refused by the plan (--max-size) before the first
# file (bones_skin0.exr was once written, then left behind).
dqskin_outcome_test(huge_skin_leaves_no_file 2 FOLDER ${hard_scratch}/huge UNCHANGED
  PREPARE bake ${rig} -o ${hard_scratch}/huge --format ply --quiet
  ARGS bake huge_skin.gltf -o ${hard_scratch}/huge --format bones,ply --backend egl --quiet
  ONE_LINE STDERR "^dqskin: huge_skin.gltf: clip wave: skin 0: the dq bone texture needs 140000 × 31 texels, over --max-size 8192")
# Two 254-byte animation names: the second folder's name is 256 bytes (the first clip's frame was written).
dqskin_outcome_test(long_animation_names_leave_no_file 2 FOLDER ${hard_scratch}/long UNCHANGED
  ARGS bake long_names.gltf -o ${hard_scratch}/long --format ply --quiet
  ONE_LINE STDERR "^dqskin: long_names.gltf: the animation's name makes the folder name 'a+\\.\\.\\.' 256 bytes long")
# A rerun that meets a file with other bytes at frame 5 has written frames 0 to 4 by then: they go again.
dqskin_outcome_test(conflict_half_way_takes_back_the_earlier_frames 2 FOLDER ${hard_scratch}/conflict UNCHANGED
  PREPARE bake ${rig} -o ${hard_scratch}/conflict --format ply --frames 5:5 --quiet
  ALTER bending_arm/bend/frame_0005.ply
  ARGS bake ${rig} -o ${hard_scratch}/conflict --format ply --quiet
  ONE_LINE STDERR "frame_0005.ply: exists with different contents. not overwritten\n$")
# Among other inputs a failed one takes back only its own files: the others and the manifest stay.
dqskin_outcome_test(failed_input_among_good_ones 1 FOLDER ${hard_scratch}/mixed
  ARGS bake ${rig} long_names.gltf -o ${hard_scratch}/mixed --format ply --quiet
  STDERR "^dqskin: long_names.gltf: the animation's name"
  PRESENT ${hard_scratch}/mixed/manifest.json ${hard_scratch}/mixed/bending_arm/bend/frame_0000.ply
  ABSENT ${hard_scratch}/mixed/long_names)
dqskin_outcome_test(render_failure_leaves_no_folder 2 FOLDER ${hard_scratch}/render_fail UNCHANGED
  ARGS render truncated_texture.gltf -o ${hard_scratch}/render_fail --frames 0:0 --size 32x32)

# ---- One clean line: library messages folded in, escapes escaped -----------------------------------------
dqskin_outcome_test(libpng_message_folded_into_render_error 2
  ARGS render truncated_texture.gltf -o ${hard_scratch}/png_render --frames 0:0 --size 32x32
  ONE_LINE STDERR "^dqskin: truncated_texture.gltf: image 0: cannot be decoded \\(")
dqskin_outcome_test(libpng_message_folded_into_diff_error 2 ARGS diff good.png truncated.png
  ONE_LINE STDERR "^dqskin: truncated.png: ")
string(ASCII 27 esc)
# ESC c resets a terminal. (No '[': CMake keeps a list's ';' inside square brackets.)
dqskin_outcome_test(file_name_with_newline_and_escape 2 ARGS info "missing\nname${esc}c.gltf"
  ONE_LINE STDERR "^dqskin: missing\\\\nname\\\\x1bc\\.gltf: No such file or directory\n$")
dqskin_outcome_test(file_name_with_newline_in_text_report 0 ARGS info "line\nbreak${esc}c.gltf"
  STDOUT "^line\\\\nbreak\\\\x1bc\\.gltf\n  scenes: 1" STDERR "^$")

# ---- Only regular files: nothing hangs -------------------------------------------------------------------
foreach(target IN ITEMS /dev/zero fifo.png zero.png)
  string(MAKE_C_IDENTIFIER "${target}" id)
  dqskin_outcome_test(diff_against_${id}_returns 2 ARGS diff good.png ${target} TIMEOUT 20
    ONE_LINE STDERR "^dqskin: ${target}: is a (device|FIFO), not a regular file\n$")
endforeach()

# ---- Absurd numbers: refused in words, no undefined conversion (the sanitizer build checks that) -----------
dqskin_outcome_test(clip_of_1e30_seconds 2 ARGS bake endless_clip.gltf -o ${hard_scratch}/endless --dry-run
  ONE_LINE STDERR "^dqskin: endless_clip.gltf: the clip would have 3e\\+31 frames \\(1e\\+30 s at 30 fps\\), more than 10000000\n$")
dqskin_outcome_test(fps_1e300 2 ARGS bake ${rig} -o ${hard_scratch}/fps --dry-run --fps 1e300
  ONE_LINE STDERR "the clip would have (inf|1e\\+300) frames")
# A clip of one key has one frame at any fps; its GIF's frame rate is clamped before it is rounded.
dqskin_outcome_test(render_still_clip_at_fps_1e300 0 FOLDER ${hard_scratch}/still
  ARGS render still_clip.gltf -o ${hard_scratch}/still --fps 1e300 --gif --size 16x16 --quiet
  PRESENT ${hard_scratch}/still/still_clip/wave/animation.gif)
dqskin_outcome_test(max_memory_not_a_size 2 ARGS info good.png --max-memory 1e400
  ONE_LINE STDERR "^dqskin: --max-memory '1e400' is not a size in bytes")

# ---- Work in proportion: memory per frame, decoded images, the plan, a bake that cannot fit its disk --------
# 1000 nodes drawing one mesh of 20000 points: a small file, 2e7 vertices to deform every frame.
dqskin_outcome_test(instances_multiply_the_frame 2 ARGS bake many_instances.gltf -o ${hard_scratch}/instances --dry-run
  ONE_LINE STDERR "^dqskin: many_instances.gltf: the scene draws 20000004 vertices a frame \\(1001 mesh instances\\). deforming one frame needs about 2.24 GiB, more than --max-memory 2.00 GiB\n$")
# Ten images declaring 8192 x 8192: render decodes them (2.5 GiB), info and bake do not.
dqskin_outcome_test(render_counts_decoded_images 2 ARGS render big_textures.gltf -o ${hard_scratch}/big_textures
  ONE_LINE STDERR "^dqskin: big_textures.gltf: loading it needs about 2.50 GiB \\(.*, 2.50 GiB of decoded images\\), more than --max-memory 2.00 GiB\n$")
dqskin_outcome_test(info_does_not_decode_images 0 ARGS info big_textures.gltf STDERR "^$")
dqskin_outcome_test(dry_run_prints_the_planned_work 0 ARGS bake ${rig} -o ${hard_scratch}/dry --dry-run --format glb,vat
  STDERR "^dry run: [0-9]+ frames to deform \\([0-9.e+]+ vertex-frames\\), up to [0-9.]+ (KiB|MiB) in [0-9]+ files. [0-9.]+ [KMGT]iB free")
# A 1 MiB file system (a tmpfs in a user and mount namespace of its own, so no root is needed): the bake is
# refused before it writes anything. Skipped, with the reason, where namespaces are not allowed.
set(small_disk ${hard_scratch}/small_disk)
set(args bake ${rig} -o ${small_disk}/out --format glb,ply,vat --fps 120)
string(REPLACE ";" "\\;" args "${args}")
set(options -DCOMMAND=$<TARGET_FILE:dqskin_cli> "-DARGS=${args}" -DEXPECTED=2 -DFOLDER=${small_disk}/out -DUNCHANGED=ON
  -DONE_LINE=ON
  "-DSTDERR_REGEX=^dqskin: ${small_disk}/out: the bake would write up to [0-9.]+ MiB in [0-9]+ files, but the file system has 1.00 MiB free")
add_test(NAME cli.hardening_bake_that_cannot_fit_is_refused_at_once
  COMMAND sh ${PROJECT_SOURCE_DIR}/app/tests/in_small_filesystem.sh 1m ${small_disk}
    ${CMAKE_COMMAND} ${options} -P ${PROJECT_SOURCE_DIR}/app/tests/expect_outcome.cmake)
set_tests_properties(cli.hardening_bake_that_cannot_fit_is_refused_at_once PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 60
  LABELS hardening)
