# One model through the player (web/CMakeLists.txt), at test time:
#   1. bakes MODEL's clip CLIP at FPS: WORK/openvat (--format vat,bones,morph --vat-profile openvat; the
#      bone texture in the dq profile), WORK/houdini (--format vat --vat-profile houdini) and WORK/morphq
#      (--format morph --max-error 0.1% --morph-quantize: fewer keys, KHR_mesh_quantization);
#   2. renders the same frames with `dqskin render --shade normals --size 256x256` into WORK/render;
#   3. installs the player into WORK/player and draws each of FRAMES through each path (openvat VAT,
#      houdini VAT, dq bones, morph glb, quantized morph glb) in headless Chromium (capture.mjs), into
#      WORK/shots, all framed on the clip's bounds in WORK/openvat's vat.json;
#   4. compares every shot with dqskin's render of that frame: `dqskin diff` must pass (or warn) with
#      --fail ${pixel} --failpercent ${percent}; and each of FAULTS (name=bake:path:frame:fault, a
#      deliberately wrong decode) must fail it.
# Prints "player: SKIPPED: <why>" (CTest's SKIP_REGULAR_EXPRESSION) when something it needs is missing.
#
#   cmake -DDQSKIN=dqskin -DNODE=node -DCHROMIUM=chromium -DSOURCE_DIR=repo -DTHREE_DIR=node_modules/three
#         -DMODEL=m.glb -DCLIP=name -DFPS=30 -DFRAMES=4,15 [-DFAULTS=n=openvat:vat:4:row-order,…]
#         [-DOPENVAT_FLAGS=--encoding,float,…] [-DCOMBINED=1] -DWORK=dir
#         -P player_test.cmake
cmake_minimum_required(VERSION 3.25)

include("${CMAKE_CURRENT_LIST_DIR}/shot_comparison.cmake")  # pixel, percent, run(), compare_shots()

macro(skip why)
  message("player: SKIPPED: ${why}")
  return()
endmacro()
foreach(need MODEL NODE CHROMIUM)
  if("${${need}}" STREQUAL "" OR "${${need}}" MATCHES "NOTFOUND$" OR NOT EXISTS "${${need}}")
    skip("${need} '${${need}}' is missing (Chromium and Node.js: scripts/install/deps.sh; the shared models: ../shared/testdata)")
  endif()
endforeach()
if(NOT EXISTS "${THREE_DIR}/build/three.module.js")
  skip("three.js is missing at ${THREE_DIR}; run scripts/install/node_tools.sh on the build folder's tools/")
endif()


file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
string(REPLACE "," ";" openvat_flags "${OPENVAT_FLAGS}")
# COMBINED: the openvat bake holds every clip in one texture (--combine-clips), so the player finds CLIP
# through the clip table.
if(COMBINED)
  set(openvat_clips --anim all --combine-clips)
else()
  set(openvat_clips --anim "${CLIP}")
endif()
run("${DQSKIN}" bake "${MODEL}" -o "${WORK}/openvat" ${openvat_clips} --fps ${FPS} --format vat,bones,morph
    --vat-profile openvat ${openvat_flags} -q)
run("${DQSKIN}" bake "${MODEL}" -o "${WORK}/houdini" --anim "${CLIP}" --fps ${FPS} --format vat --vat-profile houdini -q)
run("${DQSKIN}" bake "${MODEL}" -o "${WORK}/morphq" --anim "${CLIP}" --fps ${FPS} --format morph --max-error 0.1%
    --morph-quantize -q)
run("${DQSKIN}" render "${MODEL}" -o "${WORK}/render" --anim "${CLIP}" --fps ${FPS} --shade normals --size 256x256 -q)
run(env "THREE_DIR=${THREE_DIR}" bash "${SOURCE_DIR}/scripts/install/player.sh" "${WORK}")

get_filename_component(stem "${MODEL}" NAME_WE)
# The box dqskin render frames: the clip's bounds over its frames, as the bake measured them (its entry in
# the clip table).
file(GLOB vat_json "${WORK}/openvat/*/*/vat.json" "${WORK}/openvat/*/vat.json")
file(READ "${vat_json}" side)
string(JSON clip_count LENGTH "${side}" clips)
math(EXPR last_clip "${clip_count} - 1")
set(entry "")
foreach(i RANGE ${last_clip})
  string(JSON name GET "${side}" clips ${i} name)
  if(name STREQUAL CLIP)
    set(entry ${i})
  endif()
endforeach()
if(entry STREQUAL "")
  message(FATAL_ERROR "${vat_json}: no clip ${CLIP} in its clip table")
endif()
set(box "")
foreach(end min max)
  foreach(axis 0 1 2)
    string(JSON value GET "${side}" clips ${entry} bounds ${end} ${axis})
    list(APPEND box ${value})
  endforeach()
endforeach()
string(REPLACE ";" "," box "${box}")
string(REPLACE "," ";" frames "${FRAMES}")
string(REPLACE "," ";" faults "${FAULTS}")
set(captures "")
set(expect_pass "")
foreach(frame IN LISTS frames)
  foreach(case openvat:vat openvat:bones openvat:morph houdini:vat morphq:morph)
    string(REPLACE ":" ";" parts "${case}")
    list(GET parts 0 bake)
    list(GET parts 1 path)
    set(name ${bake}_${path}_${frame})
    list(APPEND captures "${name}=bake=../${bake}&clip=${CLIP}&path=${path}&frame=${frame}&box=${box}")
    list(APPEND expect_pass "${name}:${frame}")
  endforeach()
endforeach()
set(expect_fail "")
foreach(fault IN LISTS faults)
  string(REGEX MATCH "^([^=]+)=([^:]+):([^:]+):([0-9]+):(.+)$" match "${fault}")
  if(NOT match)
    message(FATAL_ERROR "FAULTS: '${fault}' is not name=bake:path:frame:fault")
  endif()
  set(name fault_${CMAKE_MATCH_1})
  list(APPEND captures "${name}=bake=../${CMAKE_MATCH_2}&clip=${CLIP}&path=${CMAKE_MATCH_3}&frame=${CMAKE_MATCH_4}&fault=${CMAKE_MATCH_5}")
  list(APPEND expect_fail "${name}:${CMAKE_MATCH_4}")
endforeach()
run("${NODE}" "${SOURCE_DIR}/web/capture.mjs" --root "${WORK}" --out "${WORK}/shots" --chromium "${CHROMIUM}"
    --size 256x256 ${captures})

compare_shots("the player")
