# `dqskin bake` on the command line: help, the bundled default input, exit statuses and messages.
set(bake_scratch ${CMAKE_CURRENT_BINARY_DIR}/bake_cli)
file(MAKE_DIRECTORY ${bake_scratch}/tmp)
set(rig ${PROJECT_SOURCE_DIR}/testdata/bending_arm.gltf)

include(${CMAKE_CURRENT_LIST_DIR}/cli_test.cmake)
function(dqskin_bake_test name expected)
  dqskin_cli_test(cli.bake_${name} ${expected} ${ARGN} ENVIRONMENT "TMPDIR=${bake_scratch}/tmp" ${bake_test_environment})
  set_property(TEST cli.bake_${name} APPEND PROPERTY FIXTURES_REQUIRED bake_scratch)
endfunction()
# Every run starts from an empty scratch folder (with the TMPDIR the default-input bake writes into), so
# that outputs of an earlier build are not "existing files with different contents".
add_test(NAME cli.bake_clean_scratch COMMAND sh -c "rm -rf '${bake_scratch}' && mkdir -p '${bake_scratch}/tmp'")
set_tests_properties(cli.bake_clean_scratch PROPERTIES FIXTURES_SETUP bake_scratch)

dqskin_bake_test(help 0 ARGS bake --help
  STDOUT "INPUT.*--out.*--anim.*--fps.*--frames.*--keys.*--times.*--mode.*--format.*--backend.*--shard.*--jobs.*--dry-run.*--quiet.*--json-progress.*--force.*Exit status")
dqskin_bake_test(default_input_says_where 0 ARGS bake
  STDERR "^dqskin: no input given: baking the bundled textured_cylinder.gltf into [^\n]*/dqskin-bake-[^\n]*/out\n.*manifest: ")
dqskin_bake_test(dry_run_lists_frames 0 ARGS bake ${rig} -o ${bake_scratch}/dry --dry-run --format glb,vat
  STDOUT "bending_arm/[^/]+/frame_0000.glb\n.*vat_positions.exr")
dqskin_bake_test(json_progress 0 ARGS bake ${rig} -o ${bake_scratch}/json --json-progress --format ply
  STDOUT "^{\"animation\":[^\n]*\"event\":\"progress\"[^\n]*\n.*{[^\n]*\"event\":\"summary\"[^\n]*\"stage_s\":")
dqskin_bake_test(quiet_prints_nothing 0 ARGS bake ${rig} -o ${bake_scratch}/quiet --quiet --format ply
  STDOUT "^$" STDERR "^$")
dqskin_bake_test(missing_input_exits_2 2 ARGS bake ${bake_scratch}/missing.gltf -o ${bake_scratch}/missing
  STDERR "^dqskin: [^\n]*/missing.gltf: [^\n]+\n$")
dqskin_bake_test(some_inputs_failed_exits_1 1 ARGS bake ${bake_scratch}/missing.gltf ${rig} -o ${bake_scratch}/some --quiet
  STDERR "^dqskin: [^\n]*/missing.gltf: [^\n]+\n$")
dqskin_bake_test(unknown_format_exits_2 2 ARGS bake ${rig} -o ${bake_scratch}/x --format glb,fbx
  STDERR "^dqskin: --format 'fbx' is not one of glb, ply, obj, vat, bones, morph\n$")
dqskin_bake_test(bad_shard_exits_2 2 ARGS bake ${rig} -o ${bake_scratch}/x --shard 3/3
  STDERR "^dqskin: --shard '3/3': I must be at least 0 and less than N\n$")
dqskin_bake_test(unknown_mode_exits_2 2 ARGS bake ${rig} -o ${bake_scratch}/x --mode slerp
  STDERR "^dqskin: --mode 'slerp' is not one of lbs, dqs, dib\n$")
dqskin_bake_test(dib_on_the_gpu_exits_2 2 ARGS bake ${rig} -o ${bake_scratch}/x --mode dib --backend egl
  STDERR "^dqskin: --mode dib runs on the CPU reference only")
dqskin_bake_test(dib_on_fast_cpu_exits_2 2 ARGS bake ${rig} -o ${bake_scratch}/x --mode dib --backend fast-cpu
  STDERR "^dqskin: --mode dib runs on the CPU reference only")
# Texture profiles and the planner: unknown names, a budget no choice meets (one line, no texture), and
# the plan a dry run prints.
set(twist ${PROJECT_SOURCE_DIR}/testdata/twisted_cylinder.gltf)
dqskin_bake_test(unknown_vat_profile_exits_2 2 ARGS bake ${rig} -o ${bake_scratch}/x --format vat --vat-profile unity
  STDERR "^dqskin: --vat-profile 'unity' is not one of dqskin, openvat, houdini\n$")
dqskin_bake_test(octahedral_normals_are_dqskins 2 ARGS bake ${rig} -o ${bake_scratch}/x --format vat --vat-profile openvat
  --normals oct8 STDERR "^dqskin: octahedral normals \\(oct8\\) are dqskin's; the openvat profile stores normals separate or packed\n$")
dqskin_bake_test(unknown_bones_profile_exits_2 2 ARGS bake ${rig} -o ${bake_scratch}/x --format bones --bones-profile mat2
  STDERR "^dqskin: --bones-profile 'mat2' is not one of dq, dq-cocos, mat3x4, mat4\n$")
dqskin_bake_test(bad_max_error_exits_2 2 ARGS bake ${rig} -o ${bake_scratch}/x --format vat --max-error 1mm
  STDERR "^dqskin: --max-error '1mm' is not a positive length or percentage \\(0.001, 0.1%\\)\n$")
dqskin_bake_test(unmet_max_error_exits_2 2 ARGS bake ${twist} -o ${bake_scratch}/unmet --format vat --encoding png8
  --max-error 0.00001 STDERR "^dqskin: [^\n]*twisted_cylinder.gltf: clip twist: no texture meets --max-error 10 um; the most accurate is png8 at 30 fps \\([0-9.]+ mm, [0-9.]+ KiB\\)\n$")
add_test(NAME cli.bake_unmet_max_error_leaves_nothing COMMAND sh -c
  "test ! -e '${bake_scratch}/unmet/twisted_cylinder'")
set_tests_properties(cli.bake_unmet_max_error_leaves_nothing PROPERTIES DEPENDS cli.bake_unmet_max_error_exits_2
  FIXTURES_REQUIRED bake_scratch)
dqskin_bake_test(dry_run_prints_the_plan 0 ARGS bake ${twist} -o ${bake_scratch}/plan --format vat --vat-profile openvat
  --encoding half --max-bytes 100K --dry-run STDOUT "twisted_cylinder-remap_info.json"
  STDERR "plan for clip twist \\(--max-bytes 100 KiB\\)[^\n]*\n.*\\* half +6 frames at 5 fps, 792 x 12, 55.7 KiB[^\n]*<- chosen")

# The morph-target animation: listed by a dry run, its flag refused without it, a quantization grid coarser
# than the budget refused with no file left, two bakes byte for byte the same, and its validator run.
dqskin_bake_test(morph_dry_run_lists_animation_glb 0 ARGS bake ${rig} -o ${bake_scratch}/morph_dry --format morph --dry-run
  STDOUT "^[^\n]*morph_dry/bending_arm/bend/animation.glb\n$")
dqskin_bake_test(morph_quantize_needs_morph 2 ARGS bake ${rig} -o ${bake_scratch}/x --format glb --morph-quantize
  STDERR "^dqskin: --morph-quantize is for --format morph\n$")
dqskin_bake_test(morph_unmet_grid_exits_2 2 ARGS bake ${twist} -o ${bake_scratch}/morph_unmet --format morph
  --morph-quantize --max-error 0.000001 STDERR "^dqskin: [^\n]*twisted_cylinder.gltf: clip twist: --morph-quantize's grid \\(a step of [0-9.]+ um\\) stores positions within [0-9.]+ um, over --max-error 1 um\n$")
add_test(NAME cli.bake_morph_unmet_grid_leaves_nothing COMMAND sh -c "test ! -e '${bake_scratch}/morph_unmet/twisted_cylinder'")
set_tests_properties(cli.bake_morph_unmet_grid_leaves_nothing PROPERTIES DEPENDS cli.bake_morph_unmet_grid_exits_2
  FIXTURES_REQUIRED bake_scratch)
add_test(NAME cli.bake_morph_is_deterministic COMMAND sh -c
  "for d in a b; do $<TARGET_FILE:dqskin_cli> bake ${twist} -o '${bake_scratch}/morph_'$d --format morph --max-error 0.5% --morph-quantize --quiet || exit 1; done && cmp '${bake_scratch}/morph_a/twisted_cylinder/twist/animation.glb' '${bake_scratch}/morph_b/twisted_cylinder/twist/animation.glb' && cmp '${bake_scratch}/morph_a/manifest.json' '${bake_scratch}/morph_b/manifest.json'")
set_tests_properties(cli.bake_morph_is_deterministic PROPERTIES FIXTURES_REQUIRED bake_scratch ENVIRONMENT "${bake_test_environment}")

# The summary, --verbose and the manifest say which deformer ran.
dqskin_bake_test(fast_cpu_says_so 0 ARGS bake ${rig} -o ${bake_scratch}/fast --format ply --backend fast-cpu -v
  STDERR "frames deformed on fast-cpu \\((avx2-fma|baseline)\\).*\ndeformer: fast-cpu [^\n]*; backend: fast-cpu, dqskin fast CPU deformer")
dqskin_bake_test(reference_says_so 0 ARGS bake ${rig} -o ${bake_scratch}/reference --format ply --backend cpu -v
  STDERR "frames deformed on cpu-reference .*\ndeformer: cpu-reference; backend: cpu, dqskin CPU reference")
dqskin_bake_test(auto_says_which_ran 0 ARGS bake ${rig} -o ${bake_scratch}/auto --format ply --json-progress
  STDOUT "\"deformer\":\"(gpu|fast-cpu \\((avx2-fma|baseline)\\))\"[^\n]*\"event\":\"summary\"")
dqskin_bake_test(two_frame_choices_exit_2 2 ARGS bake ${rig} -o ${bake_scratch}/x --keys --times 0,1
  STDERR "^dqskin: --frames, --keys and --times choose frames in different ways")
dqskin_bake_test(inputs_required_with_out_dir 2 ARGS bake ${rig}
  STDERR "^dqskin: -o OUTDIR is required")
dqskin_bake_test(unwritable_out_dir_exits_2 2 ARGS bake ${rig} -o /proc/dqskin-cannot-write-here --format ply
  STDERR "^dqskin: /proc/dqskin-cannot-write-here[^\n]*\n$")
dqskin_bake_test(no_gl_context_exits_3 3 ARGS bake ${rig} -o ${bake_scratch}/nogl --backend egl
  STDERR "^dqskin: no OpenGL 4.3 core context: ")
set_property(TEST cli.bake_no_gl_context_exits_3 APPEND PROPERTY ENVIRONMENT
  "__EGL_VENDOR_LIBRARY_FILENAMES=${CMAKE_CURRENT_BINARY_DIR}/no-such-vendor.json")

# Every rig and shared model baked to glb, then every frame file through the Khronos glTF-Validator
# (installed by scripts/install/node_tools.sh into the build tree; the test fails when it is missing).
set(bake_glb_dir ${CMAKE_CURRENT_BINARY_DIR}/bake_glb)
add_test(NAME cli.bake_glb_samples COMMAND ${CMAKE_COMMAND} -DCOMMAND=$<TARGET_FILE:dqskin_cli>
  -DTESTDATA=${PROJECT_SOURCE_DIR}/testdata -DSHARED=${PROJECT_SOURCE_DIR}/../shared/testdata -DOUT=${bake_glb_dir}
  -P ${PROJECT_SOURCE_DIR}/app/tests/bake_glb_samples.cmake)
set_tests_properties(cli.bake_glb_samples PROPERTIES FIXTURES_SETUP bake_glb ENVIRONMENT "${bake_test_environment}")
find_program(DQSKIN_NODE node)
add_test(NAME cli.bake_glb_validator COMMAND ${DQSKIN_NODE} ${PROJECT_SOURCE_DIR}/scripts/check/validate_gltf.mjs
  --validator ${CMAKE_BINARY_DIR}/tools/node_modules/gltf-validator ${bake_glb_dir})
set_tests_properties(cli.bake_glb_validator PROPERTIES FIXTURES_REQUIRED bake_glb)
